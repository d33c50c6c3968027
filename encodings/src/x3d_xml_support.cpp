// Parts of the XML reader that need none of its state (x3d_xml.hpp, x3d_xml_tree.hpp):
// telling XML from the other encodings, the offset-to-XML-location map, the field types of
// built-in nodes as the translation writes them, and which raw text keeps the Classic
// translation's statements apart.
#include "parser_impl.hpp"
#include "x3d_numbers.hpp"
#include "x3d_xml.hpp"
#include "x3d_xml_tree.hpp"

#include <algorithm>

namespace gs::vrml::parsing {

bool looksLikeXml(std::string_view text, bool& decided) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (xmlSpace(static_cast<char>(c)) || c == 0xEF || c == 0xBB || c == 0xBF) {
      ++i;
      continue;
    }
    decided = true;
    return c == '<';
  }
  decided = false;
  return false;
}

std::pair<int, int> OffsetLocations::at(std::size_t offset) {
  const auto before = [](std::size_t o, const Entry& e) { return o < e.offset; };
  if (entries_.empty() || offset < entries_.front().offset) return {0, 0};
  std::size_t i = std::min(cursor_, entries_.size() - 1);
  if (entries_[i].offset <= offset) {
    // Forward from the last answer: a few steps, else a search of what is left.
    for (int steps = 0; steps < 8 && i + 1 < entries_.size() && entries_[i + 1].offset <= offset;
         ++steps)
      ++i;
    if (i + 1 < entries_.size() && entries_[i + 1].offset <= offset)
      i = static_cast<std::size_t>(
              std::upper_bound(entries_.begin() + static_cast<std::ptrdiff_t>(i), entries_.end(),
                               offset, before) -
              entries_.begin()) -
          1;
  } else {
    i = static_cast<std::size_t>(
            std::upper_bound(entries_.begin(), entries_.end(), offset, before) - entries_.begin()) -
        1;
  }
  cursor_ = i;
  return {entries_[i].line, entries_[i].column};
}

std::optional<FieldType> findBuiltInFieldType(const NodeType& type, std::string_view f) {
  int i = type.findField(f);
  // X3D's names for VRML97's fields, X3D 3's names (Parser::x3dFieldAlias). (Switch's and
  // LOD's `children` are MFNode below.)
  if (i < 0 && f != "children") i = parsing::Parser::x3dFieldAlias(type, f);
  if (i >= 0) return type.fields[static_cast<std::size_t>(i)].type;
  if (f == "children" && (type.id() == NodeTypeId::Switch || type.id() == NodeTypeId::LOD))
    return FieldType::MFNode;
  return std::nullopt;
}

bool readXmlNumbers(XNode& x, std::string_view name, const char* v) {
  for (const FieldSpec& f : x.type->fields) {
    if (!sameName(f.name, name)) continue;
    const int components = plainListComponents(f.type);
    if (components == 0 || f.access == AccessType::eventIn || f.access == AccessType::eventOut)
      return false;
    XNode::Numbers& slot = x.nextNumbers();
    const bool ok = f.type == FieldType::MFInt32 ? readPlainInts(v, slot.ints)
                                                 : readPlainFloats(v, components, slot.floats);
    if (!ok) return false;
    x.addNumbers(name, f.type, components);
    return true;
  }
  return false;
}

bool rawClassicSafe(std::string_view text) {
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '#' || c == '{' || c == '}' || c == '[' || c == ']') {
      return false;
    }
  }
  return !inString;
}

}  // namespace gs::vrml::parsing
