// The config archive on its own (common/trackbed/common/archive.h): round trips of
// nested structs, lists, optionals, maps and enums in YAML and JSON, the same struct
// from both formats, and dotted-path errors for wrong types, unknown keys and
// missing required keys (at Finish, or at once).
#include "trackbed/common/archive.h"

#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/common/archive_eigen.h"

namespace trackbed::archive {
namespace {

enum class Mode { kFast, kCareful };

struct Stereo {
  double fx_px = 500.0;
  std::vector<double> distortion;
  Eigen::Vector2d center_px{320.0, 240.0};
  bool operator==(const Stereo& o) const {
    return fx_px == o.fx_px && distortion == o.distortion && center_px == o.center_px;
  }

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("fx_px", &fx_px);
    a->Visit("distortion", &distortion);
    a->Visit("center_px", &center_px);
  }
};

struct Robot {
  std::string name = "rover";
  int wheels = 4;
  std::uint64_t serial = 0;
  Mode mode = Mode::kFast;
  Stereo stereo;
  std::vector<Stereo> spares;
  std::optional<double> max_speed_mps;
  Entries<std::string> tags;
  bool operator==(const Robot& o) const {
    return name == o.name && wheels == o.wheels && serial == o.serial && mode == o.mode &&
           stereo == o.stereo && spares == o.spares && max_speed_mps == o.max_speed_mps &&
           tags == o.tags;
  }

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("name", &name, kRequired);
    a->Visit("wheels", &wheels);
    a->Visit("serial", &serial);
    a->VisitEnum("mode", &mode, {{"fast", Mode::kFast}, {"careful", Mode::kCareful}});
    a->Visit("stereo", &stereo);
    a->Visit("spares", &spares);
    a->Visit("max_speed_mps", &max_speed_mps);
    a->Visit("tags", &tags, kOmitEmpty);
  }
};

struct Config {
  Robot robot;
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("robot", &robot);
  }
};

Robot Sample() {
  Robot r;
  r.name = "scout: 2";  // needs quotes in YAML
  r.wheels = -6;
  r.serial = 18446744073709551615u;
  r.mode = Mode::kCareful;
  r.stereo.fx_px = 1.0 / 3.0;
  r.stereo.distortion = {0.1, -2e-7, 0.0};
  r.spares.resize(2);
  r.spares[1].fx_px = 612.5;
  r.max_speed_mps = 1.5;
  r.tags = {{"colour", "red"}, {"site.name", "lab"}};
  return r;
}

Robot FromYaml(const std::string& yaml) {
  Robot r;
  Read(ParseYaml(yaml), "", Wording::kDetailed, &r);
  return r;
}

Robot FromJson(const std::string& json) {
  Robot r;
  Read(ParseJson(json), "", Wording::kDetailed, &r);
  return r;
}

// The message reading `yaml` as a Config throws (empty when it does not throw).
std::string ErrorOf(const std::string& yaml, Wording wording = Wording::kDetailed) {
  try {
    Config c;
    Read(ParseYaml(yaml), "", wording, &c);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ArchiveTest, NestedStructsRoundTripExactlyInYaml) {
  const Robot r = Sample();
  const std::string yaml = ToYaml(Write(r));
  EXPECT_EQ(yaml,
            "name: \"scout: 2\"\n"
            "wheels: -6\n"
            "serial: 18446744073709551615\n"
            "mode: careful\n"
            "stereo:\n"
            "  fx_px: 0.3333333333333333\n"
            "  distortion: [0.1, -2.0e-07, 0]\n"
            "  center_px: [320, 240]\n"
            "spares:\n"
            "  - {fx_px: 500, distortion: [], center_px: [320, 240]}\n"
            "  - {fx_px: 612.5, distortion: [], center_px: [320, 240]}\n"
            "max_speed_mps: 1.5\n"
            "tags:\n"
            "  colour: red\n"
            "  site.name: lab\n");
  EXPECT_EQ(FromYaml(yaml), r);
  EXPECT_EQ(ToYaml(Write(FromYaml(yaml))), yaml);
}

TEST(ArchiveTest, NestedStructsRoundTripExactlyInJson) {
  const Robot r = Sample();
  const std::string json = ToJson(Write(r));
  EXPECT_NE(json.find("\"serial\": 18446744073709551615"), std::string::npos) << json;
  EXPECT_NE(json.find("\"fx_px\": 0.3333333333333333"), std::string::npos) << json;
  EXPECT_EQ(FromJson(json), r);
  EXPECT_EQ(ToJson(Write(FromJson(json))), json);
}

TEST(ArchiveTest, YamlAndJsonGiveTheSameStruct) {
  const Robot from_yaml = FromYaml(R"(
name: scout
wheels: 6
mode: careful
stereo: {fx_px: 612.5, distortion: [0.1, 0.2]}
spares: [{fx_px: 1}]
max_speed_mps: 2
tags: {a: x}
)");
  const Robot from_json = FromJson(R"({
  "name": "scout", "wheels": 6, "mode": "careful",
  "stereo": {"fx_px": 612.5, "distortion": [0.1, 0.2]},
  "spares": [{"fx_px": 1}], "max_speed_mps": 2, "tags": {"a": "x"}
})");
  EXPECT_EQ(from_yaml, from_json);
  EXPECT_EQ(from_yaml.stereo.fx_px, 612.5);
  EXPECT_EQ(from_yaml.spares.at(0).fx_px, 1.0);
  EXPECT_EQ(from_yaml.max_speed_mps, 2.0);
}

TEST(ArchiveTest, MissingKeysKeepDefaultsAndNullClearsOptionals) {
  Robot r = FromYaml("name: a\nstereo: {distortion: [1]}\n");
  EXPECT_EQ(r.wheels, 4);
  EXPECT_EQ(r.stereo.fx_px, 500.0);
  EXPECT_EQ(r.stereo.center_px, Eigen::Vector2d(320.0, 240.0));
  EXPECT_FALSE(r.max_speed_mps.has_value());
  r = FromYaml("name: a\nmax_speed_mps: 3\n");
  EXPECT_EQ(r.max_speed_mps, 3.0);
  Read(ParseYaml("name: a\nmax_speed_mps: null\n"), "", Wording::kDetailed, &r);
  EXPECT_FALSE(r.max_speed_mps.has_value());
  // Nothing writes as null; empty entries are left out (kOmitEmpty).
  const std::string json = ToJson(Write(Robot{}));
  EXPECT_NE(json.find("\"max_speed_mps\": null"), std::string::npos) << json;
  EXPECT_EQ(json.find("\"tags\""), std::string::npos) << json;
}

TEST(ArchiveTest, ErrorsNameTheDottedPath) {
  EXPECT_EQ(ErrorOf("robot: {name: a, stereo: {fx_px: abc}}"),
            "robot.stereo.fx_px: expected a number, got 'abc'");
  EXPECT_EQ(ErrorOf("robot: {name: a, stereo: {fx_px: \"5\"}}"),
            "robot.stereo.fx_px: expected a number, got the quoted string \"5\"");
  EXPECT_EQ(ErrorOf("robot: {name: a, spares: [{}, {distortion: [1, x]}]}"),
            "robot.spares[1].distortion[1]: expected a number, got 'x'");
  EXPECT_EQ(ErrorOf("robot: {name: a, stereo: {center_px: [1]}}"),
            "robot.stereo.center_px: expected a list of 2 numbers, got a list of 1");
  EXPECT_EQ(ErrorOf("robot: {name: a, wheels: 4.5}"),
            "robot.wheels: expected an integer, got '4.5'");
  EXPECT_EQ(ErrorOf("robot: {name: a, serial: -1}"),
            "robot.serial: expected an integer in [0, 2^64), got '-1'");
  EXPECT_EQ(ErrorOf("robot: {name: a, mode: slow}"),
            "robot.mode: must be one of fast, careful (got 'slow')");
  EXPECT_EQ(ErrorOf("robot: {name: a, stereo: 5}"), "robot.stereo: expected a map, got '5'");
  EXPECT_EQ(ErrorOf("robot: {name: a, spares: {}}"), "robot.spares: expected a list, got a map");
}

TEST(ArchiveTest, UnknownAndMissingKeysAreRejected) {
  EXPECT_EQ(ErrorOf("robot: {name: a, stereo: {fx: 1}}"),
            "robot.stereo.fx: unknown key (allowed: fx_px, distortion, center_px)");
  EXPECT_EQ(ErrorOf("robot: {wheels: 3}"), "robot.name: missing");
  // A misspelt required key is reported as the typo it is.
  EXPECT_EQ(ErrorOf("robot: {nmae: a}"),
            "robot.nmae: unknown key (allowed: name, wheels, serial, mode, stereo, spares, "
            "max_speed_mps, tags)");
  EXPECT_EQ(ErrorOf("robot: {name: a, name: b}"), "robot.name: duplicate key");
  EXPECT_EQ(ErrorOf("robot: {name: a}\nextra: 1\n"), "extra: unknown key (allowed: robot)");
}

// Keys whose absence is reported at once, as a reader going key by key would.
struct KeyByKey {
  int first = 0;
  int second = 0;
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("first", &first, kRequiredAtOnce);
    a->Visit("second", &second, kRequiredAtOnce);
  }
};

std::string KeyByKeyErrorOf(const std::string& json) {
  try {
    KeyByKey k;
    Read(ParseJson(json), "file", Wording::kDetailed, &k);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ArchiveTest, MissingAtOnceComesBeforeLaterKeysAndUnknownKeys) {
  EXPECT_EQ(KeyByKeyErrorOf(R"({"first": 1, "second": 2})"), "");
  EXPECT_EQ(KeyByKeyErrorOf(R"({"second": "x"})"), "file.first: missing");
  // A renamed key reads as the missing one, not as the unknown one.
  EXPECT_EQ(KeyByKeyErrorOf(R"({"first": 1, "secnd": 2})"), "file.second: missing");
  EXPECT_EQ(KeyByKeyErrorOf(R"({"first": 1, "second": 2, "third": 3})"),
            "file.third: unknown key (allowed: first, second)");
  EXPECT_EQ(KeyByKeyErrorOf(R"({"first": "x"})"),
            "file.first: expected an integer, got the quoted string \"x\"");
}

TEST(ArchiveTest, BriefWordingForSweepFiles) {
  EXPECT_EQ(ErrorOf("robot: {name: [a]}", Wording::kBrief),
            "robot.name: expected a string, got a list");
  EXPECT_EQ(ErrorOf("robot: {name: a, serial: -2}", Wording::kBrief),
            "robot.serial: expected a non-negative integer, got '-2'");
  EXPECT_EQ(ErrorOf("robot: {name: a, stereo: 5}", Wording::kBrief),
            "robot.stereo: expected a map, got a scalar");
  EXPECT_EQ(ErrorOf("robot: {name: a, stereo: {f: 1}}", Wording::kBrief),
            "robot.stereo.f: unknown key (expected one of: fx_px, distortion, center_px)");
}

TEST(ArchiveTest, JsonErrorsUseTheSamePaths) {
  try {
    FromJson(R"({"name": "a", "stereo": {"fx_px": "abc"}})");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.path(), "stereo.fx_px");
    EXPECT_EQ(e.reason(), "expected a number, got the quoted string \"abc\"");
  }
  EXPECT_THROW(FromJson(R"({"name": "a", "name": "b"})"), Error);
  try {
    ParseJson("{\"name\": ");
    FAIL() << "no error";
  } catch (const SyntaxError& e) {
    EXPECT_EQ(e.reason().rfind("not valid JSON: ", 0), 0u) << e.reason();
  }
}

TEST(ArchiveTest, YamlSyntaxErrorsHaveLineAndColumn) {
  try {
    ParseYaml("a: 1\nb: [1, 2\n");
    FAIL() << "no error";
  } catch (const SyntaxError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.reason().rfind("invalid YAML at line 3, column ", 0), 0u) << e.reason();
  }
}

TEST(ArchiveTest, PathsParseAndReachIntoTrees) {
  const std::optional<Path> p = ParsePath("a.b[2].c.0");
  ASSERT_TRUE(p);
  ASSERT_EQ(p->size(), 5u);
  EXPECT_EQ((*p)[2].index, 2u);
  EXPECT_TRUE((*p)[2].key.empty());
  EXPECT_EQ((*p)[4].index, 0u);
  EXPECT_FALSE(ParsePath("a..b"));
  EXPECT_FALSE(ParsePath("0.a"));
  EXPECT_FALSE(ParsePath("a[x]"));

  Node root = ParseYaml("list: [1, 2]\n");
  std::string where;
  Reach(root, *ParsePath("new.deep.key"), &where) = Node::Scalar("3", Node::Tag::kPlain);
  EXPECT_EQ(where, "new.deep.key");
  Reach(root, *ParsePath("list.1"), &where) = Node::Scalar("5", Node::Tag::kPlain);
  EXPECT_EQ(where, "list[1]");
  EXPECT_EQ(ToYaml(root), "list: [1, 5]\nnew:\n  deep:\n    key: 3\n");
  try {
    Reach(root, *ParsePath("list[2]"), &where);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "list: index 2 is past the end (2 entries)");
  }
  EXPECT_THROW(Reach(root, *ParsePath("list.a"), &where), Error);
}

TEST(ArchiveTest, EmitterHonoursStyles) {
  Node map = Node::Map();
  map.Set("name", Node::Scalar("ci", Node::Tag::kString)).set_style(Node::Style::kDoubleQuoted);
  Node& seeds = map.Set("seeds", Write(std::vector<int>{1, 2}));
  seeds.set_style(Node::Style::kFlow);
  map.Set("on", Write(true));
  EXPECT_EQ(EmitYaml(map), "name: \"ci\"\nseeds: [1, 2]\non: true");
}

TEST(ArchiveTest, DoublesAreShortestAndExact) {
  EXPECT_EQ(FormatDouble(0.1), "0.1");
  EXPECT_EQ(FormatDouble(200000.0), "200000");
  EXPECT_EQ(FormatDouble(1e-5), "0.00001");
  EXPECT_EQ(FormatDouble(1e-7), "1.0e-07");
  EXPECT_EQ(FormatDouble(-1.0 / 0.0), "-.inf");
  EXPECT_EQ(ParseDouble("+2.5"), 2.5);
  EXPECT_FALSE(ParseDouble("1e999"));
  EXPECT_FALSE(ParseDouble("0x10"));
  EXPECT_EQ(ParseSigned("010"), 10);
}

}  // namespace
}  // namespace trackbed::archive
