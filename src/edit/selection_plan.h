// The order in which to evaluate a selection that combines other selections: each
// selection it reaches once, operands before the selections that use them, and when each
// result is last needed. Made without recursion, so a chain of 10^5 selections neither
// overflows the stack nor evaluates anything twice (a chain of unions of the previous one
// twice would otherwise take 2^n evaluations); time and memory are linear in the document.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "edit/edit_document.h"

namespace glint {

struct SelectionPlan {
  struct Step {
    const Selection* selection;
    std::vector<size_t> operands;  // indices of earlier steps, in the selection's operand order
  };
  std::vector<Step> steps;  // the last one is the selection asked for
  std::vector<size_t> uses;  // per step: how many operand references later steps make to it
};

// The plan for selection `name` of a valid document (parseEditDocument: names resolve, no
// cycles).
SelectionPlan planSelection(const EditDocument& document, const std::string& name);

// Runs a plan: evaluate(selection, operandMasks) gives each step's mask from its operands'
// masks (pointers, in operand order). A mask is released once its last user has run, so a
// chain holds two masks at a time.
template <typename Mask, typename Evaluate>
Mask evaluatePlan(const SelectionPlan& plan, Evaluate&& evaluate) {
  std::vector<std::optional<Mask>> masks(plan.steps.size());
  std::vector<size_t> uses = plan.uses;
  std::vector<const Mask*> operands;
  for (size_t i = 0; i < plan.steps.size(); ++i) {
    const SelectionPlan::Step& step = plan.steps[i];
    operands.clear();
    for (size_t k : step.operands) operands.push_back(&*masks[k]);
    masks[i] = evaluate(*step.selection, operands);
    for (size_t k : step.operands)
      if (--uses[k] == 0) masks[k].reset();
  }
  return std::move(*masks.back());
}

}  // namespace glint
