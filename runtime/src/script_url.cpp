// classifyScriptUrl (script_host.hpp): what a Script url entry names.
#include "base/text.hpp"
#include "runtime/script_host.hpp"

#include <cctype>

namespace gs::runtime {

ScriptUrlEntry classifyScriptUrl(std::string_view entry) {
  while (!entry.empty() && std::isspace(static_cast<unsigned char>(entry.front())))
    entry.remove_prefix(1);
  ScriptUrlEntry out;
  out.text = entry;
  for (std::string_view scheme : {"javascript:", "ecmascript:", "vrmlscript:"}) {
    if (base::startsWithNoCase(entry, scheme)) {
      out.kind = ScriptUrlEntry::Kind::inlineSource;
      out.scheme = scheme;
      out.text = entry.substr(scheme.size());
      return out;
    }
  }
  if (entry.empty()) return out;
  const std::string_view classSuffix = ".class";
  const bool classFile =
      entry.size() >= classSuffix.size() &&
      base::startsWithNoCase(entry.substr(entry.size() - classSuffix.size()), classSuffix);
  out.kind = classFile || base::startsWithNoCase(entry, "java:") ? ScriptUrlEntry::Kind::java
                                                                 : ScriptUrlEntry::Kind::file;
  return out;
}

}  // namespace gs::runtime
