#include "parallax/core/error.h"

namespace parallax {

namespace {

bool isFieldCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

}  // namespace

std::string spellFields(const std::string& text,
                        const std::function<std::string(const std::string& field)>& spell) {
  std::string out;
  out.reserve(text.size());
  size_t at = 0;
  while (at < text.size()) {
    const size_t open = text.find('{', at);
    if (open == std::string::npos) break;
    size_t close = open + 1;
    while (close < text.size() && isFieldCharacter(text[close])) ++close;
    const bool field = close < text.size() && text[close] == '}' && close > open + 1 &&
                       text[open + 1] >= 'a' && text[open + 1] <= 'z';
    out.append(text, at, open - at);
    if (field) {
      out += spell(text.substr(open + 1, close - open - 1));
      at = close + 1;
    } else {
      out += '{';
      at = open + 1;
    }
  }
  out.append(text, at, std::string::npos);
  return out;
}

std::string errorText(const InputError& error,
                      const std::function<std::string(const std::string& field)>& spell,
                      const std::function<std::string(const std::string& field,
                                                      const std::string& value)>& withValue) {
  if (const auto* request = dynamic_cast<const RequestError*>(&error)) {
    const std::string subject = request->value().empty()
                                    ? spell(request->field())
                                    : withValue(request->field(), request->value());
    return subject + ": " + spellFields(request->message(), spell);
  }
  // A display (or other description) the request made, refused under a key of the file it
  // stands for: "/gap_mm: message", with no file to name.
  const std::string text = error.what(), prefix = std::string(RequestError::kRequestSource) + ": ";
  if (error.file() == RequestError::kRequestSource && text.rfind(prefix, 0) == 0)
    return spellFields(text.substr(prefix.size()), spell);
  return spellFields(text, spell);
}

}  // namespace parallax
