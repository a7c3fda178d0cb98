// YAML and JSON text to and from the config archive's Node tree (archive.h): yaml-cpp
// and nlohmann::json parse and emit, the archive keeps their scalars as text so that
// it, not they, decides what a number is.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <nlohmann/json.hpp>

#include "trackbed/common/archive.h"

namespace trackbed::archive {

namespace {

// ---------------------------------------------------------------------------
// YAML in.

Node FromYaml(const YAML::Node& y, const std::string& path) {
  switch (y.Type()) {
    case YAML::NodeType::Scalar:
      // yaml-cpp tags non-plain (quoted) scalars "!"; explicit tags count as plain.
      return Node::Scalar(y.Scalar(), y.Tag() == "!" ? Node::Tag::kString : Node::Tag::kPlain);
    case YAML::NodeType::Sequence: {
      Node list = Node::List();
      for (std::size_t i = 0; i < y.size(); ++i) {
        list.items().push_back(FromYaml(y[i], JoinIndex(path, i)));
      }
      return list;
    }
    case YAML::NodeType::Map: {
      Node map = Node::Map();
      for (const auto& entry : y) {
        if (!entry.first.IsScalar()) {
          throw Error(path, "expected names as keys, got " +
                                Describe(FromYaml(entry.first, path), Wording::kDetailed));
        }
        const std::string key = entry.first.Scalar();
        if (map.Find(key)) throw Error(JoinKey(path, key), "duplicate key");
        map.entries().emplace_back(key, FromYaml(entry.second, JoinKey(path, key)));
      }
      return map;
    }
    default:
      return Node();
  }
}

// ---------------------------------------------------------------------------
// JSON in: nlohmann's SAX events, so that duplicate keys are seen and numbers keep
// their text.

using Json = nlohmann::ordered_json;

class JsonBuilder {
 public:
  explicit JsonBuilder(std::string path) : root_path_(std::move(path)) {}

  bool null() { return Put(Node()); }
  bool boolean(bool b) { return Put(Node::Scalar(b ? "true" : "false", Node::Tag::kBool)); }
  bool number_integer(Json::number_integer_t x) {
    return Put(Node::Scalar(std::to_string(x), Node::Tag::kInteger));
  }
  bool number_unsigned(Json::number_unsigned_t x) {
    return Put(Node::Scalar(std::to_string(x), Node::Tag::kInteger));
  }
  bool number_float(Json::number_float_t, const Json::string_t& text) {
    return Put(Node::Scalar(text, Node::Tag::kFloat));
  }
  bool string(Json::string_t& s) { return Put(Node::Scalar(s, Node::Tag::kString)); }
  bool binary(Json::binary_t&) { return false; }  // not produced by text parsing
  bool start_object(std::size_t) { return Open(Node::Map()); }
  bool start_array(std::size_t) { return Open(Node::List()); }
  bool end_object() { return Close(); }
  bool end_array() { return Close(); }
  bool key(Json::string_t& k) {
    if (open_.back().node->Find(k)) {
      error_ = Error(JoinKey(open_.back().path, k), "duplicate key");
      return false;
    }
    key_ = k;
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception& e) {
    syntax_error_ =
        SyntaxError(root_path_, std::string("not valid JSON: ") + e.what(), 0, 0, e.what());
    return false;
  }

  Node Take() {
    if (syntax_error_) throw *syntax_error_;
    if (error_) throw *error_;
    return std::move(root_);
  }

 private:
  struct OpenContainer {
    Node* node;
    std::string path;
  };

  // Where the next value goes, and its path.
  std::pair<Node*, std::string> Slot() {
    if (open_.empty()) return {&root_, root_path_};
    OpenContainer& top = open_.back();
    if (top.node->IsList()) {
      top.node->items().emplace_back();
      return {&top.node->items().back(), JoinIndex(top.path, top.node->items().size() - 1)};
    }
    top.node->entries().emplace_back(key_, Node());
    return {&top.node->entries().back().second, JoinKey(top.path, key_)};
  }

  bool Put(Node n) {
    *Slot().first = std::move(n);
    return true;
  }

  // Only the innermost open container grows, so pointers to the outer ones stay valid.
  bool Open(Node n) {
    auto [slot, path] = Slot();
    *slot = std::move(n);
    open_.push_back({slot, std::move(path)});
    return true;
  }

  bool Close() {
    open_.pop_back();
    return true;
  }

  std::string root_path_;
  Node root_;
  std::vector<OpenContainer> open_;
  std::string key_;
  std::optional<Error> error_;
  std::optional<SyntaxError> syntax_error_;
};

// ---------------------------------------------------------------------------
// YAML out, the archive's own layout.

/// A rendered value: its one-line form (scalar, flow list or flow map) and, for maps
/// and lists of maps, its block form (lines, unindented).
struct Text {
  std::string line;
  std::vector<std::string> block;
};

// Lists of maps are written one entry per line when every entry fits in this width;
// longer flow lists are wrapped to it.
constexpr std::size_t kMaxFlowWidth = 90;

Text Render(const Node& node);

// A long flow list over several lines, breaking between entries.
std::vector<std::string> Wrap(const std::vector<Text>& entries) {
  std::vector<std::string> lines = {"["};
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string piece = entries[i].line + (i + 1 < entries.size() ? "," : "]");
    if (i > 0 && lines.back().size() + 1 + piece.size() > kMaxFlowWidth) lines.push_back(" ");
    lines.back() += (lines.back().size() > 1 ? " " : "") + piece;
  }
  return lines;
}

// Lists of maps as block lists (entries as flow maps when all fit), other lists as flow lists.
Text RenderList(const Node& node) {
  if (node.size() == 0) return {"[]", {}};
  Text list;
  std::vector<Text> entries;
  for (const Node& item : node.items()) {
    entries.push_back(Render(item));
    list.line += (list.line.empty() ? "[" : ", ") + entries.back().line;
  }
  list.line += "]";
  if (entries.front().block.empty()) {
    if (list.line.size() > kMaxFlowWidth) list.block = Wrap(entries);
    return list;
  }
  const bool flow = std::all_of(entries.begin(), entries.end(),
                                [](const Text& e) { return e.line.size() <= kMaxFlowWidth; });
  for (const Text& e : entries) {
    if (flow) list.block.push_back("- " + e.line);
    for (std::size_t i = 0; !flow && i < e.block.size(); ++i) {
      list.block.push_back((i == 0 ? "- " : "  ") + e.block[i]);
    }
  }
  return list;
}

Text RenderMap(const Node& node) {
  Text map;
  for (const auto& [k, value] : node.entries()) {
    const std::string key = FormatString(k);
    const Text text = Render(value);
    map.line += (map.line.empty() ? "{" : ", ") + key + ": " + text.line;
    if (text.block.empty()) {
      map.block.push_back(key + ": " + text.line);
    } else {
      map.block.push_back(key + ":");
      for (const std::string& l : text.block) map.block.push_back("  " + l);
    }
  }
  map.line = map.line.empty() ? "{}" : map.line + "}";
  return map;
}

Text Render(const Node& node) {
  switch (node.type()) {
    case Node::Type::kScalar:
      return {node.tag() == Node::Tag::kString ? FormatString(node.text()) : node.text(), {}};
    case Node::Type::kList:
      return RenderList(node);
    case Node::Type::kMap:
      return RenderMap(node);
    case Node::Type::kNull:
      break;
  }
  return {"null", {}};
}

// ---------------------------------------------------------------------------
// YAML out through yaml-cpp's emitter.

void Emit(YAML::Emitter& out, const Node& node) {
  if (node.style() == Node::Style::kFlow && (node.IsList() || node.IsMap())) out << YAML::Flow;
  switch (node.type()) {
    case Node::Type::kNull:
      out << YAML::Null;
      break;
    case Node::Type::kScalar:
      if (node.style() == Node::Style::kDoubleQuoted) out << YAML::DoubleQuoted;
      if (node.tag() == Node::Tag::kBool) {
        out << (node.text() == "true");
      } else {
        out << node.text();
      }
      break;
    case Node::Type::kList:
      out << YAML::BeginSeq;
      for (const Node& item : node.items()) Emit(out, item);
      out << YAML::EndSeq;
      break;
    case Node::Type::kMap:
      out << YAML::BeginMap;
      for (const auto& [key, value] : node.entries()) {
        out << YAML::Key << key << YAML::Value;
        Emit(out, value);
      }
      out << YAML::EndMap;
      break;
  }
}

// ---------------------------------------------------------------------------
// JSON out.

Json NumberJson(const std::string& text) {
  if (!text.empty() && text[0] == '-') {
    if (const std::optional<long long> i = ParseSigned(text)) return Json(*i);
  } else if (const std::optional<unsigned long long> u = ParseUnsigned(text)) {
    return Json(*u);
  }
  const std::optional<double> x = ParseDouble(text);
  return x && std::isfinite(*x) ? Json(*x) : Json();
}

Json ScalarJson(const Node& node) {
  switch (node.tag()) {
    case Node::Tag::kString:
      return Json(node.text());
    case Node::Tag::kBool:
      return Json(node.text() == "true");
    case Node::Tag::kInteger:
      return NumberJson(node.text());
    case Node::Tag::kFloat: {
      const std::optional<double> x = ParseDouble(node.text());
      return x && std::isfinite(*x) ? Json(*x) : Json();
    }
    case Node::Tag::kPlain:
      break;
  }
  // A plain YAML scalar: a number or a bool if it reads as one, else a string.
  if (ParseDouble(node.text())) return NumberJson(node.text());
  if (const std::optional<bool> b = ParseBool(node.text())) return Json(*b);
  return Json(node.text());
}

Json ToJsonValue(const Node& node) {
  switch (node.type()) {
    case Node::Type::kScalar:
      return ScalarJson(node);
    case Node::Type::kList: {
      Json list = Json::array();
      for (const Node& item : node.items()) list.push_back(ToJsonValue(item));
      return list;
    }
    case Node::Type::kMap: {
      Json map = Json::object();
      for (const auto& [key, value] : node.entries()) map[key] = ToJsonValue(value);
      return map;
    }
    case Node::Type::kNull:
      break;
  }
  return Json();
}

// Whether `text` is well-formed UTF-8 (RFC 3629: no overlong forms, surrogates or code
// points above U+10FFFF), as the JSON writer requires.
bool IsUtf8(const std::string& text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto byte = [&text](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char b = byte(i);
    const std::size_t n = b < 0x80   ? 1
                          : b < 0xC2 ? 0
                          : b < 0xE0 ? 2
                          : b < 0xF0 ? 3
                          : b < 0xF5 ? 4
                                     : 0;
    if (n == 0 || i + n > text.size()) return false;
    for (std::size_t k = 1; k < n; ++k) {
      if ((byte(i + k) & 0xC0) != 0x80) return false;
    }
    const unsigned char second = n > 1 ? byte(i + 1) : 0x80;
    if ((b == 0xE0 && second < 0xA0) || (b == 0xED && second > 0x9F) ||
        (b == 0xF0 && second < 0x90) || (b == 0xF4 && second > 0x8F)) {
      return false;
    }
    i += n;
  }
  return true;
}

// The dotted key of the first key or scalar in `node` that is not UTF-8. YAML is UTF-8
// text, and what is read ends up in JSON files (a sweep's cells.json and summary.json)
// and the run folder's scenario.yaml, whose writers would fail or write invalid text long
// after the file was accepted; raw bytes and escapes (`"\uD800"`) alike.
std::optional<std::string> NonUtf8Key(const Node& node, const std::string& path) {
  if (node.IsScalar()) return IsUtf8(node.text()) ? std::nullopt : std::optional(path);
  for (std::size_t i = 0; i < node.items().size(); ++i) {
    if (auto bad = NonUtf8Key(node.items()[i], JoinIndex(path, i))) return bad;
  }
  for (const auto& [key, value] : node.entries()) {
    const std::string where = JoinKey(path, key);
    if (!IsUtf8(key)) return where;
    if (auto bad = NonUtf8Key(value, where)) return bad;
  }
  return std::nullopt;
}

}  // namespace

Node ParseYaml(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    const bool known = !e.mark.is_null();
    const int line = known ? e.mark.line + 1 : 0, column = known ? e.mark.column + 1 : 0;
    throw SyntaxError(path,
                      known ? "invalid YAML at line " + std::to_string(line) + ", column " +
                                  std::to_string(column) + ": " + e.msg
                            : "invalid YAML: " + e.msg,
                      line, column, e.msg);
  }
  Node node = FromYaml(root, path);
  if (const std::optional<std::string> bad = NonUtf8Key(node, path)) {
    throw Error(*bad, "not UTF-8 text");
  }
  return node;
}

Node ParseJson(const std::string& text, const std::string& path) {
  JsonBuilder builder(path);
  Json::sax_parse(text, &builder);
  return builder.Take();
}

std::string ToYaml(const Node& node) {
  const Text text = Render(node);
  std::string out;
  if (text.block.empty()) return text.line + "\n";
  for (const std::string& line : text.block) out += line + "\n";
  return out;
}

std::string EmitYaml(const Node& node) {
  YAML::Emitter out;
  Emit(out, node);
  return out.c_str();
}

std::string ToJson(const Node& node, int indent) { return ToJsonValue(node).dump(indent); }

}  // namespace trackbed::archive
