#!/usr/bin/env python3
"""Checks .ci/function_length.py on small C++ fixtures: which functions it finds too long, under
which name and first line, and what it must leave alone (classes, data, braces in literals).
Usage: function_length_test.py   (exit 0: every case as expected)"""
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "function_length.py")


def statements(n, indent="    "):
    """n lines of statements."""
    return "".join(f"{indent}x += {k};\n" for k in range(n))


def function(head, lines, indent=""):
    """A definition `head {` ... `}` that spans exactly `lines` lines."""
    return f"{indent}{head} {{\n" + statements(lines - 2, indent + "    ") + f"{indent}}}\n"


# (what it shows, the fixture's text, the lines the script must print)
CASES = [
    ("an 80-line function passes", function("int f(int x)", 80), []),
    ("an 81-line function fails", "// one line first\n" + function("int f(int x)", 81),
     ["f.cpp:2 f 81"]),
    ("a long class of short inline members passes",
     "struct Big {\n" + "".join(function(f"int m{k}(int x)", 4, "    ") for k in range(40)) +
     "};\n", []),
    ("an inline member over the limit fails under its class's name",
     "namespace n {\nclass Big {\npublic:\n" + function("int run(int x) const", 81, "    ") +
     "};\n}  // namespace n\n", ["f.cpp:4 Big::run 81"]),
    ("an out-of-class member definition over the limit fails",
     "namespace a::b {\n" + function("std::vector<int> Inserter::step(int x)", 90) + "}\n",
     ["f.cpp:2 Inserter::step 90"]),
    ("a lambda is part of its function",
     "void outer() {\n    auto f = [&](int x) {\n" + statements(40, "        ") + "    };\n" +
     statements(40) + "}\n", ["f.cpp:1 outer 84"]),
    ("a constructor's braced member initialisers are not its body",
     "A::A(int v)\n    : m_a{v},\n      m_b{v + 1} {\n" + statements(79) + "}\n",
     ["f.cpp:1 A::A 83"]),
    ("operators and templates are named",
     function("template <class F>\nbool operator==(const std::function<void()>& a, F b)", 81),
     ["f.cpp:2 operator== 81"]),
    ("long data at namespace scope passes",
     "const std::map<int, int> kTable = {\n" + "".join(f"    {{{k}, {k}}},\n" for k in range(99)) +
     "};\nenum class E {\n" + "".join(f"    e{k},\n" for k in range(99)) + "};\n", []),
    ("braces in strings, characters, comments and directives do not count",
     "const char* s() { return \"{{{\"; }\nchar c() { return '{'; }\n// {\n/* { */\n"
     "#define OPEN {\nconst char* r() { return R\"x({)\")x\"; }\n" + function("void g()", 81) +
     function("void h()", 80), ["f.cpp:7 g 81"]),
    ("--max sets the limit", function("void f()", 10), ["f.cpp:1 f 10"]),
]


def run_case(name, text, expected, tmp):
    path = os.path.join(tmp, "f.cpp")
    with open(path, "w") as f:
        f.write(text)
    limit = ["--max", "9"] if name.startswith("--max") else []
    r = subprocess.run([sys.executable, SCRIPT] + limit + ["f.cpp"], cwd=tmp,
                       capture_output=True, text=True)
    got = r.stdout.splitlines() if r.returncode else []
    if r.returncode not in (0, 1) or got != expected or (r.returncode == 1) != bool(expected):
        print(f"FAIL {name}: exit {r.returncode}, printed {r.stdout!r} {r.stderr!r}; "
              f"expected {expected}")
        return False
    print(f"ok   {name}")
    return True


def main():
    with tempfile.TemporaryDirectory() as tmp:
        results = [run_case(name, text, expected, tmp) for name, text, expected in CASES]
        # A folder stands for its core/, ui/ and app/ .cpp files (not git: every one there).
        os.makedirs(os.path.join(tmp, "tree", "core"))
        os.makedirs(os.path.join(tmp, "tree", "tests"))
        with open(os.path.join(tmp, "tree", "core", "a.cpp"), "w") as f:
            f.write(function("void a()", 81))
        with open(os.path.join(tmp, "tree", "tests", "t.cpp"), "w") as f:
            f.write(function("void t()", 200))
        r = subprocess.run([sys.executable, SCRIPT, os.path.join(tmp, "tree")],
                           capture_output=True, text=True)
        folder_ok = r.returncode == 1 and r.stdout.splitlines() == ["core/a.cpp:1 a 81"]
        print(("ok  " if folder_ok else "FAIL") + " a folder means its core/, ui/ and app/"
              + ("" if folder_ok else f": {r.returncode} {r.stdout!r} {r.stderr!r}"))
        results.append(folder_ok)
    failed = results.count(False)
    print(f"function length script: {len(results) - failed} of {len(results)} cases as expected")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
