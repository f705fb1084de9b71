#!/usr/bin/env python3
"""Functions longer than a limit (80 lines), each as `file:line name length`; exit 1 if any.

A function runs from the line of its name to the line of its closing brace. Counted: functions
at namespace scope, out-of-class member definitions (`Inserter::stepImpl`) and member functions
defined inside a class body (`BigInt::ofDouble`); a lambda, a local class or a nested block is
part of the function it is in. Not functions: classes themselves, enums, initialisers of data
(`const Table kTable = {...};`), constructor initialiser lists. Comments, strings, character
literals and preprocessor lines are skipped, so braces in them do not count.

Usage: function_length.py [--max N] [PATH...]
  A PATH that is a file is checked; a folder stands for the .cpp and .h files of its core/, ui/
  and app/ (the ones git lists there: tracked, or untracked and not ignored). Default: this
  repository.
"""
import argparse
import os
import re
import subprocess
import sys

LIMIT = 80
FOLDERS = ("core", "ui", "app")
EXTENSIONS = (".cpp", ".h")

# ---- Tokens --------------------------------------------------------------------------------

TOKEN = re.compile(
    r"""(?P<raw>(?:u8|[uUL])?R"(?P<delim>[^ ()\\\t\n]{0,16})\()"""  # raw string: to )delim"
    r"""|(?P<str>(?:u8|[uUL])?"(?:\\.|[^"\\\n])*")"""
    r"""|(?P<chr>(?:u8|[uUL])?'(?:\\.|[^'\\\n])+')"""
    r"""|(?P<line_comment>//[^\n]*)"""
    r"""|(?P<block_comment>/\*.*?\*/)"""
    r"""|(?P<num>\.?\d(?:'?[\w.]|[eEpP][+-])*)"""
    r"""|(?P<id>[A-Za-z_]\w*)"""
    r"""|(?P<punct>::|->|\[\[|\]\]|[^\s\w])"""
    r"""|(?P<newline>\n)"""
    r"""|(?P<space>[ \t\r\f\v]+)""",
    re.S,
)


def tokens(text):
    """(kind, text, line) for the code: no comments, no preprocessor lines, literals as "S"."""
    out = []
    line = 1
    pos = 0
    at_line_start = True
    while pos < len(text):
        if at_line_start and re.match(r"[ \t]*#", text[pos:pos + 256]):
            end = directive_end(text, pos)  # with its continuations and any comment in it
            line += text.count("\n", pos, end)
            pos = end
            continue
        m = TOKEN.match(text, pos)
        if not m:  # a stray character (a backslash, an unmatched quote): skip it
            pos += 1
            continue
        kind = m.lastgroup
        value = m.group(0)
        if m.group("raw") is not None:
            kind = "str"
            close = ")" + m.group("delim") + '"'
            end = text.find(close, m.end())
            end = len(text) if end < 0 else end + len(close)
            value = text[pos:end]
        else:
            end = m.end()
        if kind == "newline":
            at_line_start = True
        elif kind not in ("space", "block_comment", "line_comment"):
            at_line_start = False
            out.append((kind, "S" if kind in ("str", "chr") else value, line))
        elif kind == "block_comment" and "\n" in value:
            at_line_start = False
        line += value.count("\n")
        pos = end
    return out


def directive_end(text, pos):
    """Where the preprocessor line at pos ends: its last newline, not counting continuations."""
    end = pos
    while True:
        nl = text.find("\n", end)
        if nl < 0:
            return len(text)
        piece = re.sub(r'"(?:\\.|[^"\\\n])*"', "", text[end:nl])
        piece = re.sub(r"/\*.*?\*/", "", piece)
        if piece.endswith("\\") or "/*" in re.sub(r"//.*", "", piece):
            close = text.find("*/", nl) if "/*" in piece else nl
            end = (close if close >= 0 else len(text)) + 1
            continue
        return nl


# ---- Scopes --------------------------------------------------------------------------------

IDENT = re.compile(r"^[A-Za-z_]\w*$")
NOT_NAMES = {"if", "for", "while", "switch", "return", "sizeof", "decltype", "alignas", "alignof",
             "noexcept", "static_assert", "requires", "catch", "throw", "new", "delete",
             "__attribute__", "__declspec"}
# What may stand between a parameter list and the ':' of a constructor's initialiser list.
BEFORE_INIT_LIST = {")", "const", "noexcept", "override", "final", "&", "&&", "mutable"}


class Scanner:
    """Walks the tokens scope by scope and records every function definition it meets."""

    def __init__(self, toks):
        self.t = toks
        self.functions = []  # (name, first line, last line)

    def closing(self, i):
        """The index of the brace that closes the one at i (the last token if none does)."""
        depth = 0
        for j in range(i, len(self.t)):
            v = self.t[j][1]
            if v == "{":
                depth += 1
            elif v == "}":
                depth -= 1
                if depth == 0:
                    return j
        return len(self.t) - 1

    def scope(self, i, prefix):
        """Declarations from i up to the '}' that closes this scope; returns the index after."""
        head = []  # indices of the tokens of the declaration being read
        while i < len(self.t):
            v = self.t[i][1]
            if v == "}":
                return i + 1
            if v == ";" or (v == ":" and head and
                            self.t[head[-1]][1] in ("public", "private", "protected")):
                head = []
                i += 1
            elif v != "{":
                head.append(i)
                i += 1
            else:
                i, done = self.block(head, i, prefix)
                head = [] if done else head + [i - 1]
        return i

    def block(self, head, i, prefix):
        """The block opening at i after the declaration `head`: (index after it, whether it
        ended the declaration: a function's or a namespace's does; a class's, an initialiser's
        or a member initialiser's braces leave it going on)."""
        vals = [self.t[k][1] for k in head]
        kind, name, at = classify(vals)
        if kind == "namespace":
            return self.scope(i + 1, prefix), True
        if kind == "class":
            return self.scope(i + 1, prefix + name + "::" if name else prefix), False
        end = self.closing(i)
        if kind == "function" and not member_initialiser(vals):
            self.functions.append((prefix + name, self.t[head[at]][2], self.t[end][2]))
            return end + 1, True
        return end + 1, False


def member_initialiser(vals):
    """`A::A() : m_x{1}, m_y{2} {`: whether the brace is a member's (after its name), not the
    body's (after ')' or '}')."""
    depth = 0
    for k, v in enumerate(vals):
        if v in ("(", "["):
            depth += 1
        elif v in (")", "]"):
            depth -= 1
        elif v == ":" and depth == 0 and k > 0 and vals[k - 1] in BEFORE_INIT_LIST:
            return vals[-1] not in (")", "}")
    return False


def skip_prefix(vals):
    """The index after any `template <...>` groups and [[attributes]] at the front."""
    k = 0
    while k < len(vals):
        if vals[k] == "template" and k + 1 < len(vals) and vals[k + 1] == "<":
            k = skip_angles(vals, k + 1)
        elif vals[k] == "[[":
            k = vals.index("]]", k) + 1 if "]]" in vals[k:] else len(vals)
        else:
            return k
    return k


def skip_angles(vals, k):
    """From the '<' at k, the index after its matching '>'."""
    depth = 0
    while k < len(vals):
        if vals[k] == "<":
            depth += 1
        elif vals[k] == ">":
            depth -= 1
            if depth == 0:
                return k + 1
        elif vals[k] in (";", "{"):
            return k
        k += 1
    return k


def parameters(vals):
    """The index of the '(' that opens a function's parameters: the first at the top level,
    outside template arguments (`std::function<void()> f` has none)."""
    k = 0
    while k < len(vals):
        v = vals[k]
        if v == "<" and k > 0 and IDENT.match(vals[k - 1]) and vals[k - 1] != "operator":
            k = skip_angles(vals, k)
            continue
        if v == "[[":
            k = vals.index("]]", k) + 1 if "]]" in vals[k:] else len(vals)
            continue
        if v == "(":
            return k
        k += 1
    return None


def function_name(vals, p):
    """The qualified name before the '(' at p (A::B::f, A::~A, operator==), and its index;
    None when what stands there is no name (a lambda, a keyword, an initialiser)."""
    for k in range(p - 1, max(p - 6, -1), -1):
        if vals[k] == "operator":
            op = "".join(vals[k + 1:p])
            if not op and p + 1 < len(vals) and vals[p + 1] == ")":
                op = "()"
            name, at = "operator" + (" " + op if IDENT.match(op[:1] or "+") else op), k
            break
    else:
        k = p - 1
        if k < 0 or not IDENT.match(vals[k]) or vals[k] in NOT_NAMES:
            return None, None
        name, at = vals[k], k
    if at > 0 and vals[at - 1] == "~":
        name, at = "~" + name, at - 1
    while at >= 2 and vals[at - 1] == "::" and IDENT.match(vals[at - 2]):
        name, at = vals[at - 2] + "::" + name, at - 2
    return name, at


def classify(vals):
    """What a brace after the declaration `vals` opens: (kind, name, index of the name), kind
    one of namespace, class, function, data."""
    k = skip_prefix(vals)
    while k < len(vals) and vals[k] in ("inline", "export", "static", "constexpr", "typedef",
                                        "friend", "virtual", "explicit", "consteval"):
        k += 1
    rest = vals[k:]
    if not rest:
        return "data", "", None
    if rest[0] == "namespace" or rest == ["extern", "S"]:
        return "namespace", "", None
    if rest[0] == "enum":
        return "data", "", None
    p = parameters(rest)
    if rest[0] in ("class", "struct", "union") and (p is None or "alignas" in rest[:p + 1]):
        names = [v for v in rest[1:] if IDENT.match(v) and v not in ("final", "alignas")]
        named = len(rest) > 1 and rest[1] not in (":", "{") and names
        return "class", names[0] if named else "", None
    before = rest[:rest.index("operator")] if "operator" in rest[:p or 0] else rest[:p or 0]
    if p is None or "=" in before:  # `auto f = [](int) {`, `T x = {`: an initialiser
        return "data", "", None
    name, at = function_name(rest, p)
    if name is None:
        return "data", "", None
    return "function", name, k + at


# ---- Files ---------------------------------------------------------------------------------

def functions_in(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    s = Scanner(tokens(text))
    i = 0
    while i < len(s.t):  # a stray '}' at file scope (#if branches) must not end the scan
        i = s.scope(i, "")
    return s.functions


def files_under(root):
    try:
        listed = subprocess.run(
            ["git", "-C", root, "ls-files", "-co", "--exclude-standard", "--"] +
            [f"{d}/*{ext}" for d in FOLDERS for ext in EXTENSIONS],
            check=True, capture_output=True, text=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        listed = [os.path.relpath(os.path.join(d, f), root)
                  for top in FOLDERS for d, _, fs in os.walk(os.path.join(root, top))
                  for f in fs if f.endswith(EXTENSIONS)]
    return sorted(os.path.join(root, f) for f in listed
                  if os.path.isfile(os.path.join(root, f)) and "/corpus/" not in f)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max", type=int, default=LIMIT, help="longest allowed, in lines")
    ap.add_argument("paths", nargs="*")
    args = ap.parse_args()
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    paths = args.paths or [root]
    files = []
    for p in paths:
        if os.path.isdir(p):
            files += [(f, os.path.relpath(f, p)) for f in files_under(p)]
        elif os.path.isfile(p):
            files.append((p, p))
        else:
            print(f"function length: {p}: no such file or folder", file=sys.stderr)
            return 2
    unique = {}  # a file named twice is checked once
    for path, shown in files:
        unique.setdefault(os.path.realpath(path), (path, shown))
    files = list(unique.values())
    long = []
    for path, shown in files:
        for name, first, last in functions_in(path):
            if last - first + 1 > args.max:
                long.append((shown, first, name, last - first + 1))
    for shown, first, name, n in sorted(long):
        print(f"{shown}:{first} {name} {n}")
    if long:
        print(f"function length: {len(long)} function(s) over {args.max} lines: split them into "
              "named steps", file=sys.stderr)
        return 1
    print(f"function length: {len(files)} files, no function over {args.max} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
