#!/usr/bin/env python3
"""Unit tests of the architecture checks in scripts/, on small synthetic source trees.

Run: python3 -m unittest discover -s scripts/tests   (or: python3 scripts/tests/test_checks.py)
"""

import contextlib
import io
import os
import shutil
import subprocess
import sys
import tempfile
import textwrap
import unittest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import check_file_length  # noqa: E402
import check_function_length  # noqa: E402
import check_include_cycles  # noqa: E402
import check_no_issue_numbers  # noqa: E402
import lint_common  # noqa: E402


class TreeTestCase(unittest.TestCase):
    """Builds a throw-away source tree and runs a check's main() on it."""

    def setUp(self):
        self._dir = tempfile.TemporaryDirectory()
        self.root = self._dir.name

    def tearDown(self):
        self._dir.cleanup()

    def write(self, rel, text):
        """Write a file of the tree (text is dedented)."""
        path = os.path.join(self.root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(textwrap.dedent(text))

    def run_check(self, module, *args):
        """(exit code, stdout) of module.main on the tree."""
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            code = module.main(["--root", self.root, *args])
        return code, out.getvalue()


def header(*includes):
    """Text of a header including the given paths."""
    return "#pragma once\n" + "".join(f'#include "{i}"\n' for i in includes)


def pub(lib, name):
    """Path of a public header inside the tree."""
    return f"{lib}/trackbed/{lib}/{name}.h"


def inc(lib, name):
    """How a public header is included."""
    return f"trackbed/{lib}/{name}.h"


class DiscoveryTest(TreeTestCase):
    def test_libraries_are_top_level_folders_with_cpp_files(self):
        self.write("alpha/a.cpp", "")
        self.write("beta/trackbed/beta/b.h", "")
        self.write("docs/x.cpp", "")
        self.write("tests/t.cpp", "")
        self.write("build-release/g.cpp", "")
        self.write("empty/readme.md", "")
        self.assertEqual(lint_common.discover_libraries(self.root), ["alpha", "beta"])

    def test_blanking_keeps_lines_and_hides_braces(self):
        text = 'a = R"x({)")x"; b = \'{\'; c = 1\'000; // {\n/* } */ d = u8"}";\n'
        code = lint_common.blank_literals(text)
        self.assertEqual(len(code), len(text))
        self.assertEqual(code.count("\n"), 2)
        self.assertNotIn("{", code)
        self.assertNotIn("}", code)
        self.assertIn("1'000", code)


class IncludeCycleTest(TreeTestCase):
    def test_unit_names(self):
        self.assertEqual(check_include_cycles.unit_of("nav/trackbed/nav/foo.h"), "nav/foo")
        self.assertEqual(check_include_cycles.unit_of("nav/foo.cpp"), "nav/foo")
        self.assertEqual(check_include_cycles.unit_of("nav/foo_tracks.h"), "nav/foo_tracks")

    def test_header_and_source_of_one_unit_is_no_cycle(self):
        self.write(pub("nav", "foo"), header(inc("nav", "bar")))
        self.write("nav/foo.cpp", f'#include "{inc("nav", "foo")}"\n')
        self.write(pub("nav", "bar"), header())
        self.write("nav/bar.cpp", f'#include "{inc("nav", "bar")}"\n')
        code, out = self.run_check(check_include_cycles)
        self.assertEqual(code, 0, out)

    def test_two_unit_cycle_through_sources(self):
        self.write(pub("nav", "a"), header())
        self.write(pub("nav", "b"), header())
        self.write("nav/a.cpp", f'#include "{inc("nav", "a")}"\n#include "{inc("nav", "b")}"\n')
        self.write("nav/b.cpp", f'#include "{inc("nav", "b")}"\n#include "{inc("nav", "a")}"\n')
        code, out = self.run_check(check_include_cycles)
        self.assertEqual(code, 1, out)
        self.assertIn("cycle of 2: nav/a -> nav/b -> nav/a", out)
        self.assertIn('nav/a.cpp:2: #include "trackbed/nav/b.h"', out)
        self.assertIn('nav/b.cpp:2: #include "trackbed/nav/a.h"', out)

    def test_three_unit_cycle_with_private_header(self):
        self.write(pub("nav", "a"), header(inc("nav", "b")))
        self.write(pub("nav", "b"), header())
        self.write("nav/b.cpp", '#include "c_tracks.h"\n')
        self.write("nav/c_tracks.h", header(inc("nav", "a")))
        code, out = self.run_check(check_include_cycles)
        self.assertEqual(code, 1, out)
        self.assertIn("cycle of 3: nav/a -> nav/b -> nav/c_tracks -> nav/a", out)
        self.assertIn("nav/b.cpp:1:", out)
        self.assertIn("nav/c_tracks.h:2:", out)
        self.assertIn("nav/trackbed/nav/a.h:2:", out)

    def test_library_cycle_without_unit_cycle(self):
        self.write(pub("sim", "world"), header())
        self.write(pub("sim", "render"), header(inc("robot", "arm")))
        self.write(pub("robot", "arm"), header())
        self.write("robot/leg.cpp", f'#include "{inc("sim", "world")}"\n')
        code, out = self.run_check(check_include_cycles)
        self.assertEqual(code, 1, out)
        self.assertNotIn("units in one include cycle", out)
        self.assertIn("cycle of 2: robot -> sim -> robot", out)

    def test_commented_and_disabled_includes_are_ignored(self):
        self.write(pub("nav", "a"), header(inc("nav", "b")))
        self.write(pub("nav", "b"), "#pragma once\n// #include \"trackbed/nav/a.h\"\n"
                   "/*\n#include \"trackbed/nav/a.h\"\n*/\n#if 0\n#include \"trackbed/nav/a.h\"\n#endif\n")
        code, out = self.run_check(check_include_cycles)
        self.assertEqual(code, 0, out)

    def test_tests_folder_is_not_a_library(self):
        self.write(pub("nav", "a"), header())
        self.write("tests/x.h", '#include "y.h"\n')
        self.write("tests/y.h", '#include "x.h"\n')
        code, out = self.run_check(check_include_cycles)
        self.assertEqual(code, 0, out)


def function_text(name, lines, body="  x += 1;"):
    """A function definition that is exactly `lines` lines long."""
    return f"void {name}(int& x) {{\n" + f"{body}\n" * (lines - 2) + "}\n"


class FunctionLengthTest(TreeTestCase):
    def functions(self, text):
        """The functions found in text, as {name: length}."""
        found = check_function_length.find_functions("x.cpp", textwrap.dedent(text))
        return {f.name: check_function_length.length(f) for f in found}

    def test_121_lines_fails_and_120_passes(self):
        self.write("nav/long.cpp", "namespace a::b {\n" + function_text("Long", 121) + "}\n")
        self.write("nav/ok.cpp", "namespace {\n" + function_text("Ok", 120) + "}\n")
        code, out = self.run_check(check_function_length)
        self.assertEqual(code, 1, out)
        self.assertIn("nav/long.cpp:2: Long is 121 lines (limit 120), lines 2-122", out)
        self.assertNotIn("nav/ok.cpp:2: Ok is", out)
        self.assertIn("  120  nav/ok.cpp:2  Ok", out)

    def test_top_option(self):
        self.write("nav/f.cpp", function_text("A", 3) + function_text("B", 5) + function_text("C", 4))
        code, out = self.run_check(check_function_length, "--top", "2")
        self.assertEqual(code, 0, out)
        self.assertIn("longest 2 of 3 functions", out)
        self.assertNotIn("f.cpp:1  A", out)

    def test_lambdas_count_toward_their_function(self):
        lam = "  auto f = [&](int y) {\n    if (y) { return [y] { return y; }(); }\n    return 0;\n  };"
        text = "void Outer() {\n" + (lam + "\n") * 30 + "}\n"
        found = self.functions(text)
        self.assertEqual(found, {"Outer": 122})
        self.write("nav/l.cpp", text)
        code, out = self.run_check(check_function_length)
        self.assertEqual(code, 1, out)
        self.assertIn("Outer is 122 lines", out)

    def test_class_with_inline_methods_is_no_function(self):
        methods = "".join(f"  int Get{k}() const {{\n    return {k};\n  }}\n" for k in range(60))
        text = ("class Big : public Base<int> {\n public:\n" + methods +
                "  Big() : a_{1}, b_(2) {}\n  int a_{0};\n  int b_ = 0;\n};\n")
        found = self.functions(text)
        self.assertEqual(len(found), 61)
        self.assertEqual(found["Get7"], 3)
        self.assertEqual(found["Big"], 1)
        self.write("nav/big.h", text)
        code, out = self.run_check(check_function_length)
        self.assertEqual(code, 0, out)

    def test_raw_strings_chars_and_comments_hide_braces(self):
        text = '''\
            std::string Text() {
              const char* a = R"js(function f() { return "}"; } {{{)js";
              char b = '{';  // } {
              /* } */ const char* c = "\\"}";
              return a;
            }
            int After() { return 1'000; }
            '''
        self.assertEqual(self.functions(text), {"Text": 6, "After": 1})

    def test_signature_forms(self):
        text = '''\
            namespace n {
            enum class Mode : int { kA, kB };
            const int kTable[] = {1, 2, 3};
            template <typename T>
            T Twice(T x) {
              return x + x;
            }
            auto Sum(int a, int b) -> int {
              return a + b;
            }
            struct Op {
              bool operator()(int x) const noexcept { return x > 0; }
            };
            Widget::Widget(int w)
                : size_{w, w},
                  name_("w") {
              Init();
            }
            const auto kSquare = [](int x) {
              return x * x;
            };
            const Table kTable = Build([](Row& r) {
              r.Fill();
            });
            Holder::Holder()
                : on_done_([this](int code) {
                    Report(code);
                  }) {
              Start();
            }
            }  // namespace n
            '''
        found = self.functions(text)
        self.assertEqual(found, {"Twice": 4, "Sum": 3, "operator()": 1,
                                 "Widget::Widget": 5, "kSquare (lambda)": 3,
                                 "kTable (lambda)": 3, "Holder::Holder": 6})

    def test_unbalanced_braces_are_an_error(self):
        self.write("nav/bad.cpp", "void F() {\n  if (x) {\n}\n")
        code, out = self.run_check(check_function_length)
        self.assertEqual(code, 1, out)
        self.assertIn("never closed", out)


class FileLengthTest(TreeTestCase):
    def test_901_lines_fails_and_900_passes(self):
        self.write("sim/long.cpp", "int x;\n" * 901)
        self.write("sim/ok.cpp", "int x;\n" * 900)
        code, out = self.run_check(check_file_length)
        self.assertEqual(code, 1, out)
        self.assertIn("sim/long.cpp:901: 901 lines, over the limit of 900", out)
        self.assertNotIn("sim/ok.cpp", out)

    def test_marked_long_file_passes_and_is_listed(self):
        marker = "// Tables.\n//\n// trackbed-lint: long-file (generated table)\n"
        self.write("sim/table.cpp", marker + "int x;\n" * 2000)
        code, out = self.run_check(check_file_length)
        self.assertEqual(code, 0, out)
        self.assertIn("sim/table.cpp:3: 2003 lines, marked: generated table", out)

    def test_marker_needs_a_reason_and_the_first_five_lines(self):
        self.write("sim/noreason.cpp", "// trackbed-lint: long-file\n" + "int x;\n" * 1000)
        self.write("sim/late.cpp", "//\n" * 5 + "// trackbed-lint: long-file (x)\n" + "int x;\n" * 1000)
        code, out = self.run_check(check_file_length)
        self.assertEqual(code, 1, out)
        self.assertIn("sim/noreason.cpp:1: long-file marker gives no reason", out)
        self.assertIn("sim/late.cpp:901: 1006 lines", out)


# Built, not written out, so that this file does not cite an issue number itself.
WORD = "issue"


class NoIssueNumbersTest(TreeTestCase):
    def test_citations_fail_naming_file_and_line(self):
        self.write("nav/field.h", f"#pragma once\n\n// the random field of {WORD} 5\n")
        self.write("docs/page.md", f"Fuzzed ({WORD.title()} #28).\n\nSee {WORD}s 24 and 27.\n")
        self.write("scenes/a.yaml", f"# {WORD.upper()}#7: a sweep\nname: a\n")
        code, out = self.run_check(check_no_issue_numbers)
        self.assertEqual(code, 1)
        self.assertIn(f'nav/field.h:3: "{WORD} 5"', out)
        self.assertIn(f'docs/page.md:1: "{WORD.title()} #28"', out)
        self.assertIn(f'docs/page.md:3: "{WORD}s 24"', out)
        self.assertIn("scenes/a.yaml:1:", out)
        self.assertIn("FAILED, 4 citation(s)", out)

    def test_words_and_links_to_public_trackers_pass(self):
        self.write("a/x.cpp", f"// t{WORD} 5; the {WORD} is moot; {WORD} numbers 1-3\n"
                              f"// github.com/MichaelGrupp/evo/{WORD}s/8 quotes it\n")
        code, out = self.run_check(check_no_issue_numbers)
        self.assertEqual(code, 0, out)

    def test_binary_files_and_build_and_hidden_folders_are_skipped(self):
        self.write("build-asan/log.txt", f"{WORD} 5\n")
        self.write(".cache/note.txt", f"{WORD} 5\n")
        with open(os.path.join(self.root, "image.png"), "wb") as f:
            f.write(b"\x89PNG\0" + f"{WORD} 5".encode())
        code, out = self.run_check(check_no_issue_numbers)
        self.assertEqual(code, 0, out)
        self.assertIn("check_no_issue_numbers: OK", out)

    @unittest.skipUnless(shutil.which("git"), "git not installed")
    def test_in_a_checkout_only_tracked_files_are_checked(self):
        self.write("tracked.md", f"{WORD} 5\n")
        self.write("untracked.md", f"{WORD} 6\n")
        subprocess.run(["git", "init", "-q", self.root], check=True)
        subprocess.run(["git", "-C", self.root, "add", "tracked.md"], check=True)
        code, out = self.run_check(check_no_issue_numbers)
        self.assertEqual(code, 1)
        self.assertIn("tracked.md:1:", out)
        self.assertNotIn("untracked.md", out)


if __name__ == "__main__":
    unittest.main()
