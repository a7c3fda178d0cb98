// The config archive's data model, scalars, dotted paths and reading (archive.h).
// Parsing and emitting YAML and JSON text live in archive_io.cpp.
#include "trackbed/common/archive.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <set>
#include <system_error>

namespace trackbed::archive {

// ---------------------------------------------------------------------------
// Node and errors.

Node Node::Scalar(std::string text, Tag tag) {
  Node n;
  n.type_ = Type::kScalar;
  n.text_ = std::move(text);
  n.tag_ = tag;
  return n;
}

Node Node::List() {
  Node n;
  n.type_ = Type::kList;
  return n;
}

Node Node::Map() {
  Node n;
  n.type_ = Type::kMap;
  return n;
}

std::size_t Node::size() const {
  if (type_ == Type::kList) return items_.size();
  if (type_ == Type::kMap) return entries_.size();
  return 0;
}

const Node* Node::Find(const std::string& key) const {
  for (const Entry& e : entries_) {
    if (e.first == key) return &e.second;
  }
  return nullptr;
}

Node* Node::Find(const std::string& key) {
  for (Entry& e : entries_) {
    if (e.first == key) return &e.second;
  }
  return nullptr;
}

Node& Node::Set(const std::string& key, Node value) {
  if (Node* existing = Find(key)) return *existing = std::move(value);
  entries_.emplace_back(key, std::move(value));
  return entries_.back().second;
}

Error::Error(std::string path, std::string reason)
    : std::runtime_error(path.empty() ? reason : path + ": " + reason),
      path_(std::move(path)),
      reason_(std::move(reason)) {}

SyntaxError::SyntaxError(std::string path, std::string reason, int line, int column,
                         std::string detail)
    : Error(std::move(path), std::move(reason)),
      line_(line),
      column_(column),
      detail_(std::move(detail)) {}

// ---------------------------------------------------------------------------
// Scalars.

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// "+5" reads as 5; "+-5" and "++5" stay malformed.
std::string WithoutPlus(const std::string& s) {
  return s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+' ? s.substr(1) : s;
}

template <class Int>
std::optional<Int> ParseWhole(const std::string& text) {
  const std::string s = WithoutPlus(text);
  Int x = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return x;
}

// Plain (unquoted) only when no YAML reader could take it for anything but this string.
bool IsPlainString(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
          c == '/')) {
      return false;
    }
  }
  static const std::set<std::string> kReserved = {"true", "false", "yes", "no",  "on",
                                                  "off",  "y",     "n",   "null"};
  return kReserved.count(Lower(s)) == 0;
}

}  // namespace

// A mantissa without a dot gets ".0", which YAML 1.1 readers such as PyYAML need to
// see a float.
std::string FormatDouble(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0 ? ".inf" : "-.inf";
  char buf[400];  // the longest shortest fixed forms (near 1.8e308, 5e-324) have < 330
  const char* end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  const std::string shortest(static_cast<const char*>(buf), end);
  const std::to_chars_result fixed =
      std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed);
  if (fixed.ec == std::errc() && fixed.ptr - buf <= static_cast<long>(shortest.size()) + 3) {
    return std::string(buf, fixed.ptr);
  }
  std::string s = shortest;
  const std::size_t e = s.find('e');
  if (e != std::string::npos && s.find('.') == std::string::npos) s.insert(e, ".0");
  return s;
}

std::optional<double> ParseDouble(const std::string& text) {
  const std::string s = WithoutPlus(text);
  const std::string lower = Lower(s);
  if (lower == ".inf") return kInf;
  if (lower == "-.inf") return -kInf;
  if (lower == ".nan") return std::numeric_limits<double>::quiet_NaN();
  double x = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

std::optional<long long> ParseSigned(const std::string& text) {
  return ParseWhole<long long>(text);
}

std::optional<unsigned long long> ParseUnsigned(const std::string& text) {
  return ParseWhole<unsigned long long>(text);
}

std::optional<bool> ParseBool(const std::string& s) {
  if (s == "true" || s == "True" || s == "TRUE") return true;
  if (s == "false" || s == "False" || s == "FALSE") return false;
  return std::nullopt;
}

std::string FormatString(const std::string& s) {
  if (IsPlainString(s)) return s;
  std::string out = "\"";
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// ---------------------------------------------------------------------------
// Paths.

std::string JoinKey(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string JoinIndex(const std::string& path, std::size_t k) {
  return path + "[" + std::to_string(k) + "]";
}

std::optional<Path> ParsePath(const std::string& dotted) {
  const auto is_name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  };
  const auto is_digits = [](const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
      return std::isdigit(static_cast<unsigned char>(c));
    });
  };
  const auto index_step = [&](const std::string& s) -> std::optional<PathStep> {
    const std::optional<unsigned long long> i = is_digits(s) ? ParseUnsigned(s) : std::nullopt;
    if (!i) return std::nullopt;
    return PathStep{"", static_cast<std::size_t>(*i)};
  };
  Path steps;
  std::size_t i = 0;
  while (true) {
    std::size_t j = i;
    while (j < dotted.size() && is_name_char(dotted[j])) ++j;
    const std::string token = dotted.substr(i, j - i);
    if (token.empty()) return std::nullopt;
    if (is_digits(token)) {
      const std::optional<PathStep> step = index_step(token);
      if (!step) return std::nullopt;
      steps.push_back(*step);
    } else {
      steps.push_back({token, 0});
    }
    for (i = j; i < dotted.size() && dotted[i] == '[';) {
      j = dotted.find(']', i);
      const std::optional<PathStep> step =
          j == std::string::npos ? std::nullopt : index_step(dotted.substr(i + 1, j - i - 1));
      if (!step) return std::nullopt;
      steps.push_back(*step);
      i = j + 1;
    }
    if (i == dotted.size()) break;
    if (dotted[i] != '.') return std::nullopt;
    ++i;
  }
  if (steps.front().key.empty()) return std::nullopt;
  return steps;
}

Node& Reach(Node& root, const Path& path, std::string* where) {
  where->clear();
  Node* node = &root;
  for (const PathStep& step : path) {
    if (step.key.empty()) {
      if (!node->IsList()) throw Error(*where, "is not a list");
      if (step.index >= node->size()) {
        throw Error(*where, "index " + std::to_string(step.index) + " is past the end (" +
                                std::to_string(node->size()) + " entries)");
      }
      *where = JoinIndex(*where, step.index);
      node = &node->items()[step.index];
    } else {
      if (node->IsNull()) *node = Node::Map();
      if (!node->IsMap()) throw Error(*where, "is not a map");
      *where = JoinKey(*where, step.key);
      Node* child = node->Find(step.key);
      node = child ? child : &node->Set(step.key, Node());
    }
  }
  return *node;
}

// ---------------------------------------------------------------------------
// Messages.

std::string Describe(const Node& node, Wording wording) {
  const bool brief = wording == Wording::kBrief;
  switch (node.type()) {
    case Node::Type::kScalar:
      return brief ? "a scalar" : DescribeValue(node, wording);
    case Node::Type::kList:
      return brief ? "a list" : "a list of " + std::to_string(node.size());
    case Node::Type::kMap:
      return "a map";
    case Node::Type::kNull:
      break;
  }
  return brief ? "null" : "nothing";
}

std::string DescribeValue(const Node& node, Wording wording) {
  if (!node.IsScalar()) return Describe(node, wording);
  return node.tag() == Node::Tag::kString ? "the quoted string \"" + node.text() + "\""
                                          : "'" + node.text() + "'";
}

// ---------------------------------------------------------------------------
// Reading.

namespace detail {

const std::string* NumberText(const Node& node) {
  return node.IsScalar() && node.tag() != Node::Tag::kString ? &node.text() : nullptr;
}

void Expected(const std::string& path, const std::string& what, const Node& node, Wording wording) {
  throw Error(path, "expected " + what + ", got " + DescribeValue(node, wording));
}

}  // namespace detail

void Codec<bool>::Read(const Node& node, const std::string& path, Wording wording, bool* value) {
  const std::string* text = detail::NumberText(node);
  const std::optional<bool> x = text ? ParseBool(*text) : std::nullopt;
  if (!x) detail::Expected(path, "true or false", node, wording);
  *value = *x;
}

void Codec<double>::Read(const Node& node, const std::string& path, Wording wording,
                         double* value) {
  const std::string* text = detail::NumberText(node);
  const std::optional<double> x = text ? ParseDouble(*text) : std::nullopt;
  if (!x) detail::Expected(path, "a number", node, wording);
  *value = *x;
}

void Codec<std::string>::Read(const Node& node, const std::string& path, Wording wording,
                              std::string* value) {
  if (!node.IsScalar()) detail::Expected(path, "a string", node, wording);
  *value = node.text();
}

Reader::Reader(const Node& node, std::string path, Wording wording)
    : node_(&node), path_(std::move(path)), wording_(wording) {
  if (!node.IsMap() && !node.IsNull()) {
    throw Error(path_, "expected a map, got " + Describe(node, wording_));
  }
}

const Node* Reader::Take(const char* key, const Field& field) {
  asked_.emplace_back(key);
  const Node* child = node_->Find(key);
  if (!child && field.required) {
    std::string reason = field.what ? std::string("missing (") + field.what + ")" : "missing";
    if (field.missing_at_once) Fail(key, reason);
    if (!missing_) missing_ = {key, std::move(reason)};
  }
  return child;
}

bool Reader::Either(bool* second, std::initializer_list<const char*> first_keys,
                    std::initializer_list<const char*> second_keys) {
  const auto any = [this](std::initializer_list<const char*> keys) {
    return std::any_of(keys.begin(), keys.end(), [this](const char* k) { return Has(k); });
  };
  const bool a = any(first_keys), b = any(second_keys);
  if (a && b) {
    using Names = std::vector<std::string>;
    Fail("", "use either " + JoinNames(Names(first_keys.begin(), first_keys.end())) + " or " +
                 JoinNames(Names(second_keys.begin(), second_keys.end())) + ", not both");
  }
  if (a || b) *second = b;
  return *second;
}

bool Reader::Has(const char* key) const { return node_->Find(key) != nullptr; }

void Reader::Finish() const {
  const char* lead = wording_ == Wording::kBrief ? "expected one of: " : "allowed: ";
  for (const Node::Entry& entry : node_->entries()) {
    if (std::find(asked_.begin(), asked_.end(), entry.first) == asked_.end()) {
      Fail(entry.first, "unknown key (" + std::string(lead) + JoinNames(asked_) + ")");
    }
  }
  // After unknown keys: a misspelt required key is better reported as the typo.
  if (missing_) Fail(missing_->first, missing_->second);
}

void Reader::Fail(const std::string& key, const std::string& reason) const {
  throw Error(key.empty() ? path_ : JoinKey(path_, key), reason);
}

std::string Reader::JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

void Writer::Fail(const std::string& key, const std::string& reason) const {
  throw Error(key, reason);
}

}  // namespace trackbed::archive
