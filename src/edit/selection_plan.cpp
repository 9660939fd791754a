// Iterative post-order walk over the selections one selection reaches.
#include "edit/selection_plan.h"

#include <map>

#include "core/error.h"

namespace glint {

SelectionPlan planSelection(const EditDocument& document, const std::string& name) {
  SelectionPlan plan;
  std::map<std::string, size_t> stepOf;  // selections already planned
  struct Pending {
    const std::string* name;
    const Selection* selection;
    size_t nextOperand = 0;
  };
  auto find = [&](const std::string& n) {
    auto it = document.selections.find(n);
    GLINT_CHECK(it != document.selections.end(), "planSelection: unknown selection " + n);
    return &*it;
  };
  auto root = find(name);
  std::vector<Pending> stack{{&root->first, &root->second}};
  while (!stack.empty()) {
    Pending& top = stack.back();
    if (top.nextOperand < top.selection->operands.size()) {
      const std::string& operand = top.selection->operands[top.nextOperand++];
      if (!stepOf.count(operand)) {
        GLINT_CHECK(stack.size() < document.selections.size(), "planSelection: selections form a cycle");
        auto entry = find(operand);
        stack.push_back({&entry->first, &entry->second});
      }
      continue;
    }
    // Every operand is planned: this selection's step follows them.
    SelectionPlan::Step step{top.selection, {}};
    for (const std::string& operand : top.selection->operands) {
      size_t k = stepOf.at(operand);
      step.operands.push_back(k);
      plan.uses[k]++;
    }
    stepOf.emplace(*top.name, plan.steps.size());
    plan.steps.push_back(std::move(step));
    plan.uses.push_back(0);
    stack.pop_back();
  }
  return plan;
}

}  // namespace glint
