#include "scene/mesh_text_scan.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/message_text.h"
#include "scene/mesh_loader.h"

namespace caligo {
namespace {

constexpr size_t npos = std::string_view::npos;

// The line of `text` that holds byte `at`, counting from 1.
size_t line_of(std::string_view text, size_t at) {
  return 1 + size_t(std::count(text.begin(), text.begin() + std::min(at, text.size()), '\n'));
}

std::string at_line(std::string_view text, size_t at) { return "line " + std::to_string(line_of(text, at)) + ": "; }

// ---- JSON (glTF) ----------------------------------------------------------------------------

// The arrays and objects outside strings; `part` (empty, or the part of the file) starts the message.
std::string json_nesting_problem(std::string_view json, const std::string& part) {
  size_t depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxGltfJsonDepth)
        return part + at_line(json, i) + "arrays and objects are nested more than " +
               std::to_string(kMaxGltfJsonDepth) + " levels deep (the glTF limit)";
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return {};
}

// ---- XML (COLLADA) --------------------------------------------------------------------------

// XML in UTF-16 or UTF-32 (which pugixml, under assimp, recognises by a byte-order mark or by
// how "<" is encoded) as one byte a character: ASCII kept, anything else 'x'. The markup the
// scans look for is all ASCII, so this keeps it and nothing else. Empty for any other text,
// which is scanned as it is.
std::string xml_markup_bytes(std::string_view data) {
  const auto starts = [&](std::string_view prefix) { return data.substr(0, prefix.size()) == prefix; };
  using namespace std::string_view_literals;
  size_t unit = 1;
  bool big_endian = false;
  if (starts("\x00\x00\xFE\xFF"sv) || starts("\x00\x00\x00<"sv)) unit = 4, big_endian = true;
  else if (starts("\xFF\xFE\x00\x00"sv) || starts("<\x00\x00\x00"sv)) unit = 4;
  else if (starts("\xFE\xFF"sv) || starts("\x00<"sv)) unit = 2, big_endian = true;
  else if (starts("\xFF\xFE"sv) || starts("<\x00"sv)) unit = 2;
  if (unit == 1) return {};
  std::string out;
  out.reserve(data.size() / unit);
  for (size_t i = 0; i + unit <= data.size(); i += unit) {
    uint32_t code = 0;
    for (size_t b = 0; b < unit; ++b) code = code << 8 | uint8_t(data[i + (big_endian ? b : unit - 1 - b)]);
    out += code < 0x80 ? char(code) : 'x';  // a byte-order mark becomes 'x', before the markup
  }
  return out;
}

struct XmlTag {
  enum Kind { kOpen, kClose, kEmpty };
  Kind kind;
  std::string_view name;
  std::string_view attributes;  // the text after the name, up to '>' (with a final '/')
  size_t offset;                // of the '<'
  size_t end;                   // just after the '>'
};

// Calls `visit(tag)` for every element tag, in order: "<name ...>" opens one (kEmpty when it
// ends "/>"), "</name>" closes one. Declarations, processing instructions, comments and CDATA
// sections are skipped, as are quoted attribute values. Never recurses.
template <typename Visit>
void for_each_xml_tag(std::string_view xml, Visit&& visit) {
  size_t i = 0;
  const auto skip_past = [&](std::string_view end) {
    const size_t at = xml.find(end, i);
    i = at == npos ? xml.size() : at + end.size();
  };
  while ((i = xml.find('<', i)) != npos) {
    const std::string_view rest = xml.substr(i);
    if (rest.rfind("<?", 0) == 0) {
      skip_past("?>");
    } else if (rest.rfind("<!--", 0) == 0) {
      skip_past("-->");
    } else if (rest.rfind("<![CDATA[", 0) == 0) {
      skip_past("]]>");
    } else if (rest.rfind("<!", 0) == 0) {  // <!DOCTYPE ...>, perhaps with an internal [subset]
      size_t brackets = 0;
      for (++i; i < xml.size() && (xml[i] != '>' || brackets > 0); ++i) {
        if (xml[i] == '[') ++brackets;
        if (xml[i] == ']' && brackets > 0) --brackets;
      }
      ++i;
    } else {
      const size_t open = i;
      const bool closing = rest.rfind("</", 0) == 0;
      const size_t name_start = open + (closing ? 2 : 1);
      char quote = 0;
      for (i = name_start; i < xml.size(); ++i) {
        const char c = xml[i];
        if (quote != 0) {
          if (c == quote) quote = 0;
        } else if (c == '"' || c == '\'') {
          quote = c;
        } else if (c == '>') {
          break;
        }
      }
      const std::string_view tag = xml.substr(name_start, i - name_start);
      const size_t name_end = std::min(tag.find_first_of(" \t\r\n/"), tag.size());
      const XmlTag::Kind kind = closing ? XmlTag::kClose
                                : (i < xml.size() && xml[i - 1] == '/') ? XmlTag::kEmpty
                                                                         : XmlTag::kOpen;
      ++i;
      visit(XmlTag{kind, tag.substr(0, name_end), tag.substr(name_end), open, std::min(i, xml.size())});
    }
  }
}

// The value of the attribute `name` in a tag's attribute text; nullopt when it is absent (or
// the text is malformed, which the library refuses).
std::optional<std::string_view> xml_attribute(std::string_view attributes, std::string_view name) {
  constexpr const char* kSpace = " \t\r\n";
  for (size_t i = 0;;) {
    i = attributes.find_first_not_of(" \t\r\n/", i);
    if (i == npos) return std::nullopt;
    const size_t name_end = std::min(attributes.find_first_of(" \t\r\n=", i), attributes.size());
    const std::string_view attribute = attributes.substr(i, name_end - i);
    i = attributes.find_first_not_of(kSpace, name_end);
    if (i == npos || attributes[i] != '=') return std::nullopt;
    i = attributes.find_first_not_of(kSpace, i + 1);
    if (i == npos || (attributes[i] != '"' && attributes[i] != '\'')) return std::nullopt;
    const size_t close = attributes.find(attributes[i], i + 1);
    if (close == npos) return std::nullopt;
    if (attribute == name) return attributes.substr(i + 1, close - i - 1);
    i = close + 1;
  }
}

// ---- COLLADA accessors ----------------------------------------------------------------------

// A count, stride or offset: decimal digits below 2^32 (what assimp reads as unsigned int), or
// `absent` when there is no such attribute. nullopt for anything else (hex, entities, signs,
// huge numbers), which the scan refuses rather than guess how pugixml would read it.
std::optional<uint64_t> collada_number(const XmlTag& tag, std::string_view attribute, uint64_t absent) {
  const std::optional<std::string_view> text = xml_attribute(tag.attributes, attribute);
  if (!text) return absent;
  uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (ec != std::errc() || end != text->data() + text->size() || text->empty() ||
      value > std::numeric_limits<uint32_t>::max())
    return std::nullopt;
  return value;
}

// Lists of indices and counts. assimp 5.2 reads a <p> number by number, skipping only spaces,
// tabs and line ends between them: at any other character (a vertical tab, found by fuzzing) it
// stops advancing and appends zeros until memory runs out. So these hold digits, signs and
// those separators only, as text with nothing inside (no comment, CDATA or character reference,
// which pugixml would turn into other characters).
bool is_collada_index_list(std::string_view name) { return name == "p" || name == "vcount" || name == "h" || name == "v"; }

// An index list (<p>, <vcount>, <v>...): whole numbers from 0 to 2^32 - 2 between blanks.
// assimp 5.2 reads "-3", 4294967295 and 4294967296 all as vertex 0, without a word.
std::string index_list_problem(std::string_view xml, const XmlTag& tag) {
  const size_t next = std::min(xml.find('<', tag.end), xml.size());
  const std::string_view text = xml.substr(tag.end, next - tag.end);
  const auto refuse = [&](const std::string& what) {
    return at_line(xml, tag.offset) + "a <" + std::string(tag.name) + "> holds " + what +
           "; it may hold only whole numbers from 0 to 4294967294 separated by spaces, tabs and line ends";
  };
  if (const size_t bad = text.find_first_not_of("0123456789 \t\r\n"); bad != npos)
    return refuse("the character " + quote_for_message(text.substr(bad, 1)));
  if (xml.compare(next, 2, "</") != 0) return refuse("markup");
  for (size_t at = text.find_first_of("0123456789"); at != npos; at = text.find_first_of("0123456789", at)) {
    const size_t end = std::min(text.find_first_not_of("0123456789", at), text.size());
    const std::string_view number = text.substr(at, end - at);
    const size_t digits = number.size() - std::min(number.find_first_not_of('0'), number.size());
    if (digits > 10 || (digits == 10 && number.substr(number.size() - 10) > "4294967294"))
      return refuse("the index " + std::string(number));
    at = end;
  }
  return {};
}

bool is_collada_array(std::string_view name) {
  return name == "float_array" || name == "int_array" || name == "Name_array" || name == "IDREF_array" ||
         name == "bool_array";
}

struct ColladaAccessor {
  std::string_view source;  // without its '#'
  uint64_t count = 0, stride = 1, offset = 0, params = 0;
  size_t at = 0;            // the offset of its tag in the text
  // The values it reads: `count` items `stride` apart, each `max(stride, params)` long (assimp
  // reads a value for each <param>, whatever the stride). Below 2^64: each number is below 2^32.
  uint64_t extent() const { return count == 0 ? 0 : offset + (count - 1) * stride + std::max(stride, params); }
};

// What the scan gathers: the smallest count declared for each array id (assimp keeps one per
// id) and every accessor.
struct ColladaSources {
  std::unordered_map<std::string_view, uint64_t> array_counts;
  std::vector<ColladaAccessor> accessors;
  bool in_accessor = false;
  std::string problem;
};

void gather_collada_tag(std::string_view xml, const XmlTag& tag, ColladaSources& s) {
  const auto refuse = [&](const char* attribute) {
    s.problem = at_line(xml, tag.offset) + "the <" + std::string(tag.name) + "> " + attribute +
                " must be a whole number below 2^32";
  };
  if (tag.kind == XmlTag::kClose) {
    if (tag.name == "accessor") s.in_accessor = false;
    return;
  }
  if (tag.kind == XmlTag::kOpen && is_collada_index_list(tag.name)) {
    s.problem = index_list_problem(xml, tag);
  } else if (is_collada_array(tag.name)) {
    const std::optional<uint64_t> count = collada_number(tag, "count", 0);  // assimp's default
    if (!count) return refuse("count");
    const std::string_view id = xml_attribute(tag.attributes, "id").value_or("");
    // pugixml would decode "&#97;" and the like: an id the scan could not match to its users.
    if (id.find('&') != npos)
      s.problem = at_line(xml, tag.offset) + "the <" + std::string(tag.name) + "> id " + quote_for_message(id) +
                  " holds a character reference, which the file's accessors cannot be checked against";
    const auto [it, added] = s.array_counts.emplace(id, *count);
    if (!added) it->second = std::min(it->second, *count);
  } else if (tag.name == "accessor") {
    ColladaAccessor a;
    a.at = tag.offset;
    a.source = xml_attribute(tag.attributes, "source").value_or("");
    if (!a.source.empty() && a.source.front() == '#') a.source.remove_prefix(1);
    if (a.source.find('&') != npos)
      s.problem = at_line(xml, tag.offset) + "the <accessor> source " + quote_for_message(a.source) +
                  " holds a character reference, which the scan cannot match to its array";
    const std::optional<uint64_t> count = collada_number(tag, "count", 0), stride = collada_number(tag, "stride", 1),
                                  offset = collada_number(tag, "offset", 0);
    if (!count || !stride || !offset) return refuse(!count ? "count" : !stride ? "stride" : "offset");
    a.count = *count, a.stride = *stride, a.offset = *offset;
    s.accessors.push_back(a);
    s.in_accessor = tag.kind == XmlTag::kOpen;
  } else if (tag.name == "param" && s.in_accessor) {
    ++s.accessors.back().params;
  }
}

std::string xml_nesting_problem(std::string_view xml) {
  size_t depth = 0;
  std::string problem;
  for_each_xml_tag(xml, [&](const XmlTag& tag) {
    if (!problem.empty() || tag.kind == XmlTag::kEmpty) return;
    if (tag.kind == XmlTag::kClose) {
      depth -= depth > 0 ? 1 : 0;
    } else if (++depth > kMaxColladaDepth) {
      problem = at_line(xml, tag.offset) + "elements are nested more than " + std::to_string(kMaxColladaDepth) +
                " levels deep (the COLLADA limit)";
    }
  });
  return problem;
}

std::string accessor_problem(std::string_view xml) {
  ColladaSources sources;
  for_each_xml_tag(xml, [&](const XmlTag& tag) {
    if (sources.problem.empty()) gather_collada_tag(xml, tag, sources);
  });
  if (!sources.problem.empty()) return sources.problem;
  for (const ColladaAccessor& a : sources.accessors) {
    const auto array = sources.array_counts.find(a.source);
    // assimp refuses an accessor of a missing array (character references are refused above).
    if (array == sources.array_counts.end() || a.extent() <= array->second) continue;
    std::string reference(1, '#');  // (built in two steps: GCC 12 warns, wrongly, on "#" + string)
    reference += a.source;
    return at_line(xml, a.at) + "an accessor reads " + std::to_string(a.extent()) + " values from " +
           quote_for_message(reference) + ", which holds " + std::to_string(array->second);
  }
  return {};
}

// Runs `scan` on each text a reader may take the file for, until one has a problem: what
// assimp 5.2 parses (the bytes up to the first NUL, as UTF-8, whatever a byte-order mark says:
// pugixml's load_string), and, for a file in UTF-16 or UTF-32, its markup, for a reader that
// decodes them.
template <typename Scan>
std::string scan_collada_texts(std::string_view file, Scan&& scan) {
  std::string problem = scan(file.substr(0, file.find('\0')));
  const std::string wide = problem.empty() ? xml_markup_bytes(file) : std::string();
  if (!wide.empty()) problem = scan(std::string_view(wide));
  return problem;
}

}  // namespace

std::string gltf_nesting_problem(std::string_view file) {
  if (file.compare(0, 4, "glTF") != 0) return json_nesting_problem(file, "");
  if (file.size() < 20) return {};
  uint32_t length = 0, type = 0;
  std::memcpy(&length, file.data() + 12, 4);  // little-endian, as GLB and the hosts we build on
  std::memcpy(&type, file.data() + 16, 4);
  return type == 0x4E4F534A ? json_nesting_problem(file.substr(20, length), "GLB JSON chunk, ") : std::string();
}

std::string collada_nesting_problem(std::string_view file) {
  return scan_collada_texts(file, [](std::string_view xml) { return xml_nesting_problem(xml); });
}

std::string collada_accessor_problem(std::string_view file) {
  return scan_collada_texts(file, [](std::string_view xml) { return accessor_problem(xml); });
}

}  // namespace caligo
