// The config archive: one strict reader and writer for every options file trackbed
// reads (scenarios, sweep files, a sweep folder's cells.json, cell.json and
// slurm/jobs.json) and for the teach map's map.json, in YAML and in JSON.
//
// After Drake's yaml_read_archive: each options struct lists its keys once, beside its
// fields, in a template member
//
//   template <class Archive>
//   void Serialize(Archive* a) {
//     a->Visit("mass_kg", &mass_kg);
//     a->VisitEnum("contact", &contact, {{"tracks", Contact::kTracks}, {"wheels", ...}});
//   }
//
// and that one list drives reading (Reader), writing (Writer) and unknown-key
// rejection. Files are parsed into a Node tree, YAML's and JSON's common data model,
// so one Serialize reads both formats. Errors carry the dotted path of the offending
// value (`robot.stereo.fx_px: expected a number, got 'abc'`). Scalars are parsed
// here with std::from_chars, not by the YAML or JSON library, so `010` is ten,
// `4096.5` is not an int and a quoted "0.1" is not a number.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "trackbed/common/option_error.h"

namespace trackbed::archive {

// ---------------------------------------------------------------------------
// Values.

/// A parsed document, or a value to write: null, a scalar, a list or a map whose
/// entries keep their order.
class Node {
 public:
  enum class Type { kNull, kScalar, kList, kMap };
  /// What a scalar is known to be. A plain YAML scalar is kPlain: the field it is
  /// read into decides whether it is a number, a bool or a string. Quoted YAML and
  /// JSON strings are kString, which never reads as a number or a bool. The Writer
  /// and the JSON parser know the rest.
  enum class Tag { kPlain, kString, kInteger, kFloat, kBool };
  /// How EmitYaml writes the node (ToYaml and ToJson ignore it).
  enum class Style { kAuto, kFlow, kDoubleQuoted };
  using Entry = std::pair<std::string, Node>;

  /// Null.
  Node() = default;
  static Node Scalar(std::string text, Tag tag);
  static Node List();
  static Node Map();

  Type type() const { return type_; }
  bool IsNull() const { return type_ == Type::kNull; }
  bool IsScalar() const { return type_ == Type::kScalar; }
  bool IsList() const { return type_ == Type::kList; }
  bool IsMap() const { return type_ == Type::kMap; }

  /// A scalar's text, as written (a string's without its quotes).
  const std::string& text() const { return text_; }
  Tag tag() const { return tag_; }
  Style style() const { return style_; }
  void set_style(Style style) { style_ = style; }

  /// A list's items.
  const std::vector<Node>& items() const { return items_; }
  std::vector<Node>& items() { return items_; }
  /// A map's entries, in order.
  const std::vector<Entry>& entries() const { return entries_; }
  std::vector<Entry>& entries() { return entries_; }
  /// Items of a list, entries of a map, 0 otherwise.
  std::size_t size() const;

  /// A map's value for `key`, or null when there is none (or this is not a map).
  const Node* Find(const std::string& key) const;
  Node* Find(const std::string& key);
  /// Sets `key` of a map, replacing its value or appending the entry.
  Node& Set(const std::string& key, Node value);

 private:
  Type type_ = Type::kNull;
  Tag tag_ = Tag::kPlain;
  Style style_ = Style::kAuto;
  std::string text_;
  std::vector<Node> items_;
  std::vector<Entry> entries_;
};

/// An invalid document or value: `path` is the dotted path of the value
/// (`scene.objects[2].radius_m`; empty for the document), `reason` says what is wrong.
class Error : public std::runtime_error {
 public:
  Error(std::string path, std::string reason);
  const std::string& path() const { return path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string path_, reason_;
};

/// Text that is not YAML or not JSON. reason() is `invalid YAML at line L, column C:
/// <detail>` or `not valid JSON: <detail>`.
class SyntaxError : public Error {
 public:
  SyntaxError(std::string path, std::string reason, int line, int column, std::string detail);
  /// 1-based position of the error; 0 when the parser gave none.
  int line() const { return line_; }
  int column() const { return column_; }
  /// The parser's own message.
  const std::string& detail() const { return detail_; }

 private:
  int line_, column_;
  std::string detail_;
};

/// Parses YAML (the first document). Throws SyntaxError, or Error for a map key that
/// is not a scalar, a duplicate key, or a key or scalar that is not UTF-8 text (YAML is
/// UTF-8; checked here once for every file and `--set` value); `path` prefixes the paths
/// in errors.
Node ParseYaml(const std::string& text, const std::string& path = "");
/// Parses JSON. Throws SyntaxError, or Error for a duplicate key.
Node ParseJson(const std::string& text, const std::string& path = "");

/// YAML in the archive's own layout, which reading gives back exactly: maps in block
/// style, lists of scalars or lists in flow style (wrapped at 90 columns), lists of
/// maps one flow map per line when each fits in 90 columns, else in block style;
/// strings quoted only when a YAML reader could take them for anything else. What a
/// run folder's scenario.yaml is written with.
std::string ToYaml(const Node& node);
/// YAML through yaml-cpp's emitter, honouring each node's Style. No trailing newline.
std::string EmitYaml(const Node& node);
/// JSON through nlohmann::json, `indent` spaces per level; non-finite numbers become
/// null. No trailing newline.
std::string ToJson(const Node& node, int indent = 2);

// ---------------------------------------------------------------------------
// Scalars, paths and messages.

/// The shortest decimal that reads back as exactly `x`, with YAML's .inf and .nan;
/// plain notation unless it is more than 3 characters longer than exponent notation
/// (200000 and 0.00001, but 1.0e-07).
std::string FormatDouble(double x);
/// A number: decimal or exponent notation, a leading '+', .inf, -.inf and .nan.
std::optional<double> ParseDouble(const std::string& text);
/// A whole decimal number (a leading '+' allowed) in the type's range.
std::optional<long long> ParseSigned(const std::string& text);
std::optional<unsigned long long> ParseUnsigned(const std::string& text);
/// true/True/TRUE or false/False/FALSE.
std::optional<bool> ParseBool(const std::string& text);
/// `s` as a YAML scalar: plain when no reader could take it for anything but this
/// string, else double-quoted with escapes.
std::string FormatString(const std::string& s);

/// One step of a dotted path: a map key, or (key empty) a list index.
struct PathStep {
  std::string key;
  std::size_t index = 0;
};
using Path = std::vector<PathStep>;

/// Parses `a.b[2].c` or `a.b.2.c`; nothing when malformed (empty names, a leading
/// index, a bad bracket).
std::optional<Path> ParsePath(const std::string& dotted);
/// `path.key` (`key` alone at the root) and `path[k]`.
std::string JoinKey(const std::string& path, const std::string& key);
std::string JoinIndex(const std::string& path, std::size_t k);

/// The node at `path` inside `root` for setting it: missing map entries are added
/// (null), null maps on the way become maps. `where` receives the dotted path reached.
/// Throws Error at the part reached: "is not a list", "is not a map", "index N is
/// past the end (M entries)".
Node& Reach(Node& root, const Path& path, std::string* where);

/// How a reader words what it found. The scenario and sweep formats had readers of
/// their own before the archive, whose messages are part of their contract.
/// kDetailed (scenario files, the teach map): `'5'`, `the quoted string "5"`, `a list of 2`,
/// `nothing`; unknown keys `(allowed: …)`; unsigned integers `an integer in [0, 2^64)`.
/// kBrief (sweep files, sweep folders): scalars as in kDetailed where a scalar was
/// expected, else `a scalar`; `a list`, `null`; unknown keys `(expected one of: …)`;
/// unsigned integers `a non-negative integer`.
enum class Wording { kDetailed, kBrief };

/// `node` where a map or a list was expected (see Wording).
std::string Describe(const Node& node, Wording wording);
/// `node` where a scalar was expected: scalars as `'text'` or `the quoted string
/// "text"`, the rest as Describe.
std::string DescribeValue(const Node& node, Wording wording);

// ---------------------------------------------------------------------------
// Reading and writing through Serialize.

/// How Visit treats one key.
struct Field {
  /// Reading: a missing key is an error (`missing`, or `missing (<what>)`), reported by
  /// Reader::Finish after unknown keys.
  bool required = false;
  const char* what = nullptr;
  /// Writing: the key is left out when the value is empty (nothing, an empty list or
  /// string, false).
  bool omit_empty = false;
  /// Reading: a missing required key is reported at its Visit, before the keys visited
  /// after it and before unknown keys. For formats whose readers went key by key before
  /// the archive (the teach map's map.json), so that a renamed key reads as missing.
  bool missing_at_once = false;
};
/// Field{true}: the key must be there.
inline constexpr Field kRequired{true, nullptr, false};
/// Field{false, nullptr, true}: written only when not empty.
inline constexpr Field kOmitEmpty{false, nullptr, true};
/// Field{true, nullptr, false, true}: the key must be there, and its absence is the first
/// error.
inline constexpr Field kRequiredAtOnce{true, nullptr, false, true};

/// How a type is read from a Node and written to one. Specialized below for scalars,
/// lists, optionals, raw Nodes and Entries; the primary template handles structs with
/// a Serialize member. Specialize it for a type whose file form is not a field list.
template <class T, class Enable = void>
struct Codec;

/// A map with keys not known in advance, in file order.
template <class T>
using Entries = std::vector<std::pair<std::string, T>>;

/// Reads `node` (at `path`, for messages) into `*value`. Keys the file leaves out keep
/// `*value`'s values. Throws Error.
template <class T>
void Read(const Node& node, const std::string& path, Wording wording, T* value) {
  Codec<T>::Read(node, path, wording, value);
}

/// `value` as a Node.
template <class T>
Node Write(const T& value) {
  return Codec<T>::Write(value);
}

/// Calls value.Validate() and rethrows its OptionError as an Error at
/// `path.<field>`, so a validation message names the dotted key like a reading one.
template <class T>
void ValidateAt(const T& value, const std::string& path) {
  try {
    value.Validate();
  } catch (const OptionError& e) {
    throw Error(JoinKey(path, e.field()), e.reason());
  }
}

/// Whether Field::omit_empty leaves the value out.
template <class T>
bool IsEmpty(const T&) {
  return false;
}
template <class T>
bool IsEmpty(const std::vector<T>& v) {
  return v.empty();
}
template <class T>
bool IsEmpty(const std::optional<T>& v) {
  return !v.has_value();
}
inline bool IsEmpty(const std::string& s) { return s.empty(); }
inline bool IsEmpty(bool b) { return !b; }

// Scalars first: Reader::VisitEnum reads enum names as strings.
namespace detail {
/// The text of a scalar that may hold a number or a bool (not a quoted string), else null.
const std::string* NumberText(const Node& node);
[[noreturn]] void Expected(const std::string& path, const std::string& what, const Node& node,
                           Wording wording);
}  // namespace detail

template <>
struct Codec<bool> {
  static void Read(const Node& node, const std::string& path, Wording wording, bool* value);
  static Node Write(bool value) { return Node::Scalar(value ? "true" : "false", Node::Tag::kBool); }
};

template <>
struct Codec<double> {
  static void Read(const Node& node, const std::string& path, Wording wording, double* value);
  static Node Write(double value) { return Node::Scalar(FormatDouble(value), Node::Tag::kFloat); }
};

template <>
struct Codec<std::string> {
  static void Read(const Node& node, const std::string& path, Wording wording, std::string* value);
  static Node Write(const std::string& value) { return Node::Scalar(value, Node::Tag::kString); }
};

/// Reads one map into a struct through its Serialize: each Visit reads its key (when
/// present) with the key's dotted path; Finish rejects the keys nobody visited.
class Reader {
 public:
  static constexpr bool kReading = true;

  /// `node` must be a map or null (an empty map); throws Error otherwise.
  Reader(const Node& node, std::string path, Wording wording);

  template <class T>
  void Visit(const char* key, T* value, Field field = {}) {
    if (const Node* child = Take(key, field)) {
      Codec<T>::Read(*child, JoinKey(path_, key), wording_, value);
    }
  }

  /// An enum written as one of `names`.
  template <class E>
  void VisitEnum(const char* key, E* value, std::initializer_list<std::pair<const char*, E>> names,
                 Field field = {}) {
    const Node* child = Take(key, field);
    if (!child) return;
    std::string name;
    Codec<std::string>::Read(*child, JoinKey(path_, key), wording_, &name);
    std::vector<std::string> allowed;
    for (const auto& [n, e] : names) {
      if (name == n) {
        *value = e;
        return;
      }
      allowed.emplace_back(n);
    }
    Fail(key, "must be one of " + JoinNames(allowed) + " (got '" + name + "')");
  }

  /// Two groups of keys that exclude each other (e.g. a twist or track speeds). Sets
  /// `*second` when the map uses the second group, clears it for the first, leaves it
  /// when the map uses neither; returns it. Throws Error when both are used.
  bool Either(bool* second, std::initializer_list<const char*> first_keys,
              std::initializer_list<const char*> second_keys);

  /// Whether the map has `key` (without visiting it).
  bool Has(const char* key) const;

  /// Rejects the keys no Visit asked for, listing those it did; then reports the first
  /// required key that was missing (but see Field::missing_at_once).
  void Finish() const;

  /// Throws Error at `path.key` (at this map for an empty key).
  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const;

  const std::string& path() const { return path_; }
  Wording wording() const { return wording_; }

  /// "a, b, c".
  static std::string JoinNames(const std::vector<std::string>& names);

 private:
  const Node* Take(const char* key, const Field& field);

  const Node* node_;
  std::string path_;
  Wording wording_;
  std::vector<std::string> asked_;
  std::optional<std::pair<std::string, std::string>> missing_;  // first required key absent
};

/// Builds a map from a struct through its Serialize, in Visit order.
class Writer {
 public:
  static constexpr bool kReading = false;

  template <class T>
  void Visit(const char* key, T* value, Field field = {}) {
    if (field.omit_empty && IsEmpty(*value)) return;
    Add(key, Codec<T>::Write(*value));
  }

  template <class E>
  void VisitEnum(const char* key, E* value, std::initializer_list<std::pair<const char*, E>> names,
                 Field = {}) {
    for (const auto& [name, e] : names) {
      if (e == *value) Add(key, Node::Scalar(name, Node::Tag::kString));
    }
  }

  bool Either(bool* second, std::initializer_list<const char*>,
              std::initializer_list<const char*>) {
    return *second;
  }

  /// Writing never fails; this keeps Serialize bodies that check what they read
  /// compiling for both archives.
  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const;

  /// Appends an entry.
  void Add(const std::string& key, Node value) {
    map_.entries().emplace_back(key, std::move(value));
  }
  /// The map built so far.
  Node Take() { return std::move(map_); }

 private:
  Node map_ = Node::Map();
};

// ---------------------------------------------------------------------------
// Codecs.

/// Structs: their Serialize.
template <class T, class Enable>
struct Codec {
  static void Read(const Node& node, const std::string& path, Wording wording, T* value) {
    Reader reader(node, path, wording);
    value->Serialize(&reader);
    reader.Finish();
  }
  static Node Write(const T& value) {
    T copy = value;  // Serialize takes its fields by pointer, for both directions
    Writer writer;
    copy.Serialize(&writer);
    return writer.Take();
  }
};

/// Integers (not bool), in the type's range.
template <class T>
struct Codec<T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>>> {
  static void Read(const Node& node, const std::string& path, Wording wording, T* value) {
    const std::string* text = detail::NumberText(node);
    if constexpr (std::is_signed_v<T>) {
      const std::optional<long long> x = text ? ParseSigned(*text) : std::nullopt;
      if (!x || *x < std::numeric_limits<T>::min() || *x > std::numeric_limits<T>::max()) {
        detail::Expected(path, "an integer", node, wording);
      }
      *value = static_cast<T>(*x);
    } else {
      const std::optional<unsigned long long> x = text ? ParseUnsigned(*text) : std::nullopt;
      if (!x || *x > std::numeric_limits<T>::max()) {
        detail::Expected(
            path,
            wording == Wording::kBrief
                ? std::string("a non-negative integer")
                : "an integer in [0, 2^" + std::to_string(std::numeric_limits<T>::digits) + ")",
            node, wording);
      }
      *value = static_cast<T>(*x);
    }
  }
  static Node Write(T value) { return Node::Scalar(std::to_string(value), Node::Tag::kInteger); }
};

/// Lists; null reads as an empty list. Reading replaces the whole list.
template <class T, class A>
struct Codec<std::vector<T, A>> {
  static void Read(const Node& node, const std::string& path, Wording wording,
                   std::vector<T, A>* value) {
    if (!node.IsNull() && !node.IsList()) {
      throw Error(path, "expected a list, got " + Describe(node, wording));
    }
    value->clear();
    value->resize(node.size());
    for (std::size_t i = 0; i < node.size(); ++i) {
      Codec<T>::Read(node.items()[i], JoinIndex(path, i), wording, &(*value)[i]);
    }
  }
  static Node Write(const std::vector<T, A>& value) {
    Node list = Node::List();
    for (const T& v : value) list.items().push_back(Codec<T>::Write(v));
    return list;
  }
};

/// Entries: a map with any keys, in order; null reads as empty.
template <class T>
struct Codec<std::vector<std::pair<std::string, T>>> {
  static void Read(const Node& node, const std::string& path, Wording wording, Entries<T>* value) {
    if (!node.IsNull() && !node.IsMap()) {
      throw Error(path, "expected a map, got " + Describe(node, wording));
    }
    value->clear();
    for (const auto& [key, child] : node.entries()) {
      value->emplace_back(key, T{});
      Codec<T>::Read(child, JoinKey(path, key), wording, &value->back().second);
    }
  }
  static Node Write(const Entries<T>& value) {
    Node map = Node::Map();
    for (const auto& [key, v] : value) map.entries().emplace_back(key, Codec<T>::Write(v));
    return map;
  }
};

/// Optional values: null reads as nothing and nothing writes as null (leave the key
/// out instead with kOmitEmpty).
template <class T>
struct Codec<std::optional<T>> {
  static void Read(const Node& node, const std::string& path, Wording wording,
                   std::optional<T>* value) {
    if (node.IsNull()) {
      value->reset();
      return;
    }
    value->emplace();
    Codec<T>::Read(node, path, wording, &**value);
  }
  static Node Write(const std::optional<T>& value) {
    return value ? Codec<T>::Write(*value) : Node();
  }
};

/// Raw values, kept as parsed for the caller to interpret.
template <>
struct Codec<Node> {
  static void Read(const Node& node, const std::string&, Wording, Node* value) { *value = node; }
  static Node Write(const Node& value) { return value; }
};

}  // namespace trackbed::archive
