// Wrapping CLI11's help text to 100 columns.
#include "app/help_formatter.h"

#include <algorithm>
#include <sstream>

namespace glint {

std::string wrapText(const std::string& text, std::size_t width) {
  std::string out;
  std::istringstream paragraphs(text);
  std::string paragraph;
  bool firstParagraph = true;
  while (std::getline(paragraphs, paragraph)) {
    if (!firstParagraph) out += '\n';
    firstParagraph = false;
    std::istringstream words(paragraph);
    std::string word, line;
    while (words >> word) {
      if (!line.empty() && line.size() + 1 + word.size() > width) {
        out += line + '\n';
        line.clear();
      }
      line += (line.empty() ? "" : " ") + word;
    }
    out += line;
  }
  return out;
}

std::string firstSentence(const std::string& text, std::size_t width) {
  std::size_t end = text.size();
  for (const char* stop : {". ", ": "}) end = std::min(end, text.find(stop));
  std::string sentence = text.substr(0, end);
  // Too long: the clause before a parenthesis or comma, else the words that fit.
  for (const char* stop : {" (", ", "})
    if (sentence.size() > width && sentence.find(stop) != std::string::npos) sentence = sentence.substr(0, sentence.find(stop));
  if (sentence.size() > width) {
    const std::size_t space = sentence.rfind(' ', width - 3);
    sentence = sentence.substr(0, space == std::string::npos ? width - 3 : space) + "...";
  }
  return sentence;
}

std::string HelpFormatter::make_option_desc(const CLI::Option* option) const {
  // Beside the name column; format_help indents the lines after the first to it.
  return wrapText(option->get_description(), kHelpWidth - get_column_width());
}

std::string HelpFormatter::make_subcommand(const CLI::App* sub) const {
  std::ostringstream out;
  CLI::detail::format_help(out, sub->get_display_name(true),
                           firstSentence(sub->get_description(), kHelpWidth - get_column_width()), get_column_width());
  return out.str();
}

std::string HelpFormatter::make_description(const CLI::App* app) const {
  const std::string description = CLI::Formatter::make_description(app);
  const bool endsLine = !description.empty() && description.back() == '\n';
  return wrapText(description, kHelpWidth) + (endsLine ? "\n" : "");
}

}  // namespace glint
