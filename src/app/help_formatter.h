// `--help` text that fits 100 columns: descriptions wrapped at word boundaries beside their
// flags, and one line per subcommand in `glint --help` (its first sentence).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace glint {

constexpr std::size_t kHelpWidth = 100;

// `text` broken at spaces into lines of at most `width` characters (a longer word keeps its
// own line), joined by '\n'; existing line breaks are kept.
std::string wrapText(const std::string& text, std::size_t width);

// The first sentence of `text` (up to the first ". " or ": "), shortened to `width` with
// "..." when it is longer.
std::string firstSentence(const std::string& text, std::size_t width);

class HelpFormatter : public CLI::Formatter {
 public:
  HelpFormatter() { column_width(32); }
  std::string make_option_desc(const CLI::Option* option) const override;
  std::string make_subcommand(const CLI::App* sub) const override;
  std::string make_description(const CLI::App* app) const override;
};

}  // namespace glint
