#!/usr/bin/env python3
"""Writes the hand-made seed inputs of tests/fuzz/corpus/<target>/ (run from anywhere).

Seeds are small, meaningful starting points for libFuzzer: each valid format feature once, each
class of error once, and the engine's degenerate shapes. Inputs that fuzzing found (crashes,
regressions) live next to them as crash-<name>; this script never touches those. The trace
seeds are cut from `dtlab trace` output: pass --dtlab PATH to regenerate them.
"""
import argparse
import os
import struct
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")

NODE = {
    "basic.node": "4 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 1 1\n",
    "one_based_markers.node": "# 1-based, one attribute, markers\n3\t2 1 1\n1 0.0 0.0 7.5 1\n2 1 0 -2 0 # c\n3 +1.0 1e0 0 1\n",
    "header_only_count.node": "3\n0 0 0\n1 2 0\n2 0 2\n",
    "crlf_bom.node": "\ufeff3 2 0 0\r\n0 0 0\r\n1 1 0\r\n2 0 1\r\n",
    "lone_cr.node": "2 2 0 0\r0 1 2\r1 3 4\r",
    "extremes.node": "4 2 0 0\n0 4.9406564584124654e-324 -1.7976931348623157e+308\n"
                     "1 1.7976931348623157e308 2.2250738585072014e-308\n2 -0 0\n3 1e-300 1e300\n",
    "zero.node": "0 2 0 0\n",
    "claims_2_31.node": "2147483648 2 0 0\n0 0 0\n",
    "claims_2_25.node": "33554432 2 0 0\n0 0 0\n",
    "claims_attrs.node": "1 2 1073741824 0\n0 0 0\n",
    "bad_dimension.node": "3 3 0 0\n",
    "bad_index.node": "3 2 0 0\n0 0 0\n2 1 1\n",
    "nan.node": "2 2 0 0\n0 nan 0\n1 1 1\n",
    "junk.node": "2 2 0 0\n0 1.5x 0\n",
    "short.node": "5 2 0 0\n0 0 0\n",
    "extra.node": "1 2 0 0\n0 0 0\n1 1 1\n",
}

XY = {
    "plain.xy": "0 0\n1 0\n0 1\n1 1\n0.5 0.5\n",
    "header.csv": "x,y\n0.5,1.5\n-2,3e-5\n1e300,-0.1\n",
    "semicolon_header.csv": "id;y;x\n7;2.5;1.5\n8;-1;4\n",
    "quoted_header.csv": "\"X\",\"Y\",\"Z\"\n1,2,3\n4,5,6\n",
    "lonlat.csv": "lon lat\n7.5 45.25\n-3 51\n",
    "crlf_bom.csv": "\ufeffx,y\r\n0.5,1.5\r\n\r\n1e300,-0.1\r\n",
    "comments.xy": "# points\n1\t2 # first\n\n  3 4\n",
    "decimal_comma.csv": "1,5;2,5\n",
    "three_columns.csv": "1,2,3\n4,5,6\n",
    "count_first.xy": "3\n0 0\n1 1\n",
    "inf.csv": "x,y\ninf,0\n",
    "plus_signs.csv": "+1,+2\n-0,+0\n",
    "ragged.csv": "x,y\n1,2\n3\n",
    "out_of_range.csv": "1e400,0\n",
}

PTS = {
    "sample.pts": "3\n0.5,0.25,0\n1,2,0\n-3,4,0\n",
    "blanks.pts": "2\n1 2\n3 4\n",
    "z.pts": "2\n1,2,5\n3,4,0\n",
    "zero.pts": "0\n",
    "claims_2_31.pts": "2147483648\n0,0\n",
    "claims_many.pts": "1000\n0,0\n",
    "four_fields.pts": "1\n1,2,3,4\n",
    "count_comma.pts": "1,2\n3,4\n",
    "negative.pts": "-1\n",
    "extra.pts": "1\n0,0\n1,1\n",
}

# read_file: the first byte picks the extension (see fuzz_read_file.cpp kExtensions).
EXT = {".node": 0, ".pts": 1, ".csv": 2, ".xy": 3, ".txt": 4, ".dat": 5, ".NODE": 6, ".Csv": 7,
       "": 8, ".in": 9, ".node.bak": 10}
READ_FILE = {
    "node": (".node", NODE["basic.node"]),
    "sniff_node": ("", NODE["one_based_markers.node"]),
    "sniff_pts": (".in", PTS["sample.pts"]),
    "sniff_xy": (".node.bak", XY["plain.xy"]),
    "upper_node": (".NODE", NODE["crlf_bom.node"]),
    "csv": (".Csv", XY["header.csv"]),
    "pts": (".pts", PTS["blanks.pts"]),
    "empty": ("", ""),
    "binary": (".dat", "\x00\x01\x02\x03"),
    "latin1": (".txt", "# caf\xe9\n1 2\n3 4\n"),
}

# Trace lines that are wrong in one way each (the valid ones come from dtlab trace).
TRACE_BAD = {
    "not_json.jsonl": "{\"i\":0,\n",
    "not_object.jsonl": "[1,2,3]\n",
    "unknown_op.jsonl": "{\"i\":0,\"op\":\"Teleport\"}\n",
    "op_newline.jsonl": "{\"i\":0,\"op\":\"Flip\\nrm -rf\"}\n",
    "bad_change.jsonl": "{\"i\":0,\"op\":\"Flip\",\"changes\":[[\"W\",1,2,3]]}\n",
    "short_change.jsonl": "{\"i\":0,\"op\":\"Flip\",\"changes\":[[\"V\",1,2]]}\n",
    "float_sign.jsonl": "{\"i\":0,\"op\":\"InCircleTest\",\"sign\":1e300}\n",
    "huge_corner.jsonl": "{\"i\":0,\"op\":\"Flip\",\"changes\":[[\"O\",4294967297,0,1]]}\n",
    "negative_index.jsonl": "{\"i\":-1,\"op\":\"Start\"}\n",
    "blank_lines.jsonl": "\n\r\n{\"i\":0,\"op\":\"Start\",\"vertex\":-1,\"a\":0,\"b\":1}\n\n",
}


# corner_expr: the first byte picks the mesh (0 finished, 1 super mid-run, 2 ghost mid-run,
# 3 empty, 4-7 the same corrupted) and c; the rest is the expression.
CORNER_EXPR = {
    "nested": (0, "r(o(n(7)))"),
    "chain": (0, "c.n.o.r"),
    "identity": (0, "o(o(c)) == c"),
    "vertex_compare": (0, "V[n(o(c))] == V[p(c)]"),
    "point": (0, "G[v(c)]"),
    "triangle": (0, "t(s(u(c)))"),
    "not_equal": (1, "v(c) != v(n(c))"),
    "ghost_point": (2, "G[v(p(c))]"),
    "boundary": (0, "n(-1)"),
    "empty_mesh": (3, "o(c)"),
    "corrupt": (4, "o(o(o(c))) = c"),
    "corrupt_super": (5, "V[O[c]]"),
    "unbound": (0, "x.n"),
    "syntax": (0, "r(o(n(7)"),
    "deep": (0, "(" * 60 + "c" + ")" * 60),
    "big_number": (0, "n(99999999999999999999)"),
}


# lesson: the committed lessons are copied too (see main); these are wrong in one way each.
LESSON_BAD = {
    "not_toml.toml": "title = \"unclosed\n",
    "unknown_key.toml": "title = \"t\"\npoints = [[0, 0], [1, 0], [0, 1]]\ncolour = \"red\"\n",
    "bad_points.toml": "title = \"t\"\npoints = [[0, 0], [1], [0, \"x\"]]\n",
    "nan_point.toml": "title = \"t\"\npoints = [[0, 0], [nan, 0], [0, 1]]\n",
    "escape_file.toml": "title = \"t\"\npoints_file = \"../../etc/passwd\"\n",
    "bad_stop.toml": "title = \"t\"\npoints = [[0, 0], [1, 0], [0, 1]]\n[[stop]]\nrun_to = \"nowhere:7\"\n",
    "bad_answer.toml": "title = \"t\"\npoints = [[0, 0], [1, 0], [0, 1]]\n[[stop]]\nquestion = \"q\"\nanswer = \"o(o(\"\n",
    "unreachable.toml": "title = \"t\"\npoints = [[0, 0], [1, 0], [0, 1]]\n[[stop]]\nrun_to = \"inserted:99\"\n",
    "unclosed_bold.toml": "title = \"t\"\npoints = [[0, 0], [1, 0], [0, 1]]\n[[stop]]\ntext = \"**bold\"\n",
}


# trace_diff: the first byte holds the diff options (bit 0 all ops, bit 1 corners); the rest is
# a student's trace. Our own trace seeds (from dtlab trace) are added in main.
TRACE_DIFF = {
    "minimal": (0, '{"op":"Start","triangles":[[0,0,1,2]]}\n{"op":"Split","triangles":[[0,0,1,4],[1,1,2,4],[2,2,0,4]]}\n'),
    "huge_triangle": (0, '{"op":"Start","triangles":[[2147483647,0,1,2]]}\n'),
    "huge_corner": (2, '{"op":"Start","changes":[["V",536870912,-1,0]]}\n'),
    "negative_vertex": (0, '{"op":"Split","triangles":[[0,-5,1,2]]}\n'),
    "finalize_empty": (1, '{"op":"Start","triangles":[[0,0,1,2]]}\n{"op":"Finalize"}\n'),
    "no_op": (0, '{"triangles":[]}\n'),
    "not_json": (0, "Split 0 1 2\n"),
}


def lattice_circle(r):
    return [(x, y) for x in range(-r, r + 1) for y in range(-r, r + 1) if x * x + y * y == r * r]


def engine_seeds():
    """Binary inputs for fuzz_engine.cpp: header bytes, then commands (see its byte layout)."""
    def header(flags=0, seed=1, w=16, h=16, probe=128, exp=0, ox=4, oy=4):
        # exp is stored as int8 * 8; ox/oy as range(-4, 4) -> byte value (v + 4)
        return bytes([flags, seed, w - 1, h - 1, probe, (exp // 8) & 0xFF, ox, oy])

    def grid(x, y):
        return bytes([0, x + 8, y + 8])

    seeds = {}
    # 3x3 lattice, exact mode, walk locator, input order (bits 3-4 = 0).
    seeds["grid3x3"] = header() + b"".join(grid(x, y) for x in range(-1, 2) for y in range(-1, 2))
    # The same in every locator and order, super mode.
    for loc in range(4):
        for order in range(3):
            flags = 1 | (loc << 1) | (order << 3)
            seeds[f"grid_super_l{loc}_o{order}"] = header(flags=flags) + b"".join(
                grid(x, y) for x in range(-2, 3) for y in range(-2, 3, 2))
    # Cocircular: all 36 lattice points of the circle of radius 65, plus its centre.
    seeds["circle65"] = header(flags=0x20) + bytes([4, 3, 8, 8]) + b"\xff" * 8 + grid(0, 0)
    seeds["circle5_centre"] = header() + bytes([4, 1, 8, 8]) + b"\xff" * 8 + grid(0, 0) + grid(1, 0)
    # Collinear runs, then one point off the line; all collinear; duplicates.
    seeds["collinear_then_off"] = header() + bytes([3, 8, 8, 4, 4, 9]) + grid(3, -5)
    seeds["all_collinear"] = header() + bytes([3, 0, 0, 5, 6, 9]) + bytes([3, 2, 3, 5, 6, 5])
    seeds["duplicates"] = header() + grid(0, 0) + bytes([9, 8, 8, 4]) + grid(1, 1) + bytes([2, 0, 2, 1]) + grid(2, 0)
    # Points on edges: midpoints of lattice points.
    seeds["midpoints"] = header() + grid(-4, -4) + grid(4, -4) + grid(0, 4) + bytes([5, 0, 1, 5, 1, 2, 5, 2, 0, 5, 3, 4])
    # Huge, tiny and mixed magnitudes; a big offset with tiny spacing.
    seeds["huge"] = header(exp=960) + b"".join(grid(x, y) for x, y in [(0, 0), (3, 1), (1, 3), (2, 2), (-3, 1)])
    seeds["tiny_subnormal"] = header(exp=-1024) + b"".join(grid(x, y) for x, y in [(0, 0), (3, 1), (1, 3), (2, 2), (1, 1)])
    seeds["mixed_scales"] = header(exp=-256) + grid(0, 0) + grid(1, 0) + grid(0, 1) + bytes([7, 127]) + grid(1, 1) + grid(-2, 3) + bytes([7, 0]) + grid(5, 5)
    seeds["offset"] = header(exp=-40, ox=8, oy=0) + b"".join(grid(x, y) for x in range(-2, 3) for y in range(-2, 3))
    # Raw doubles: extremes of the double range next to ordinary points.
    raw = lambda x, y: bytes([6]) + struct.pack("<d", x) + struct.pack("<d", y)
    seeds["raw_extremes"] = header() + raw(1.7976931348623157e308, -1.7976931348623157e308) + raw(-1.7976931348623157e308, 1.7976931348623157e308) + raw(5e-324, 0.0) + raw(0.0, 5e-324) + raw(1.0, 1.0) + raw(-0.0, 0.0)
    seeds["raw_span"] = header(flags=1) + raw(1e-300, 1e-300) + raw(1e300, 0) + raw(0, 1e300) + raw(1e-300, 2e-300)
    # The ID buffer with a 1x1 and a 64x1 buffer, cloud points.
    seeds["idbuffer_cloud"] = header(flags=6 | (2 << 3), w=1, h=1) + b"".join(bytes([8, (i * 37) & 0xFF, (i * 91) & 0xFF]) for i in range(40))
    seeds["idbuffer_wide"] = header(flags=6 | (1 << 3), w=64, h=1, probe=255) + b"".join(grid(x % 7 - 3, x // 7 - 3) for x in range(0, 49, 3))
    seeds["empty"] = b""
    seeds["one_point"] = header() + grid(1, 1)
    return seeds


# settings: the GUI's settings.json; a good one, and damaged ones (kept aside when read).
SETTINGS = {
    "good.json": '{"window": {"x": 10, "y": 20, "width": 1280, "height": 720}, "presentation": false,\n'
                 ' "lessons": {"lessons/05_flips.toml": {"title": "Flips", "stop": 3, "furthest": 5,'
                 ' "answers": [0, 2, 1, 0, 0, 0]}}}\n',
    "typo.json": '{"presentation": tru, "lessons": {}}\n',
    "not_object.json": '[1, 2, 3]\n',
    "wrong_types.json": '{"window": "big", "lessons": {"a.toml": {"stop": "x", "answers": [9, -1]}}}\n',
    "truncated.json": '{"lessons": {"a.toml": {"title": "A", "furthest"',
    "empty.json": "",
}


# Deep nesting beside a bad field: the reader's error path (which finds the line, quotes the
# value) must hold whatever its parser held. 200000 levels overflow any recursion.
DEEP = 200000
DEEP_BAD = {
    "session": ("deep_nesting_bad_points.json",
                '{"format": "delaunay-lab session", "version": 1,\n "deep": ' + "[" * DEEP + "]" * DEEP
                + ',\n "points": "bad"}\n'),
    "trace": ("deep_nesting_bad_integer.jsonl",
              '{"i":0,"op":"Flip","a":' + "[" * DEEP + "]" * DEEP + "}\n"),
    "trace_diff": ("deep_nesting_bad_change",
                   '\x00{"op":"Flip","changes":[' + "[" * DEEP + "]" * DEEP + "]}\n"),
    "settings": ("deep_nesting_bad_lessons.json",
                 '{"deep": ' + "[" * DEEP + "]" * DEEP + ', "lessons": 7, "presentation": tru}\n'),
    "lesson": ("deep_nesting_bad_points.toml",
               'title = "t"\ndeep = ' + "[" * DEEP + "]" * DEEP + '\npoints = "bad"\n'),
}


def write(target, name, content):
    d = os.path.join(CORPUS, target)
    os.makedirs(d, exist_ok=True)
    data = content if isinstance(content, bytes) else content.encode("latin-1" if "\xe9" in content else "utf-8")
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def trace_seeds(dtlab):
    with tempfile.TemporaryDirectory() as tmp:
        pts = os.path.join(tmp, "p.xy")
        with open(pts, "w") as f:
            f.write("0 0\n4 0\n0 4\n4 4\n2 2\n2 0\n2 2\n1 3\n")
        out = os.path.join(tmp, "t.jsonl")
        for name, args in {"exact_walk": [], "super_naive": ["--boundary", "super", "--locate", "naive", "--order", "input"]}.items():
            subprocess.run([dtlab, "trace", pts, "-o", out] + args, check=True, stdout=subprocess.DEVNULL)
            with open(out) as f:
                lines = f.read().splitlines()
            # A short run keeps every op type: Start, walk, splits, tests, flips, a duplicate, Finalize.
            write("trace", f"{name}.jsonl", "\n".join(lines[:40] + lines[-3:]) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--dtlab", help="path of dtlab, to regenerate the trace seeds")
    args = ap.parse_args()
    for name, text in NODE.items():
        write("node", name, text)
    for name, text in XY.items():
        write("xy", name, text)
    for name, text in PTS.items():
        write("pts", name, text)
    for name, (ext, text) in READ_FILE.items():
        write("read_file", name, bytes([EXT[ext]]) + text.encode("latin-1" if "\xe9" in text else "utf-8"))
    for name, text in TRACE_BAD.items():
        write("trace", name, text)
    for name, (mesh, text) in CORNER_EXPR.items():
        write("corner_expr", name, bytes([mesh]) + text.encode())
    for name, text in LESSON_BAD.items():
        write("lesson", name, text)
    lessons = os.path.join(HERE, "..", "..", "lessons")
    for name in sorted(os.listdir(lessons)) if os.path.isdir(lessons) else []:
        if name.endswith(".toml"):
            with open(os.path.join(lessons, name), "rb") as f:
                write("lesson", name, f.read())
    for name, (flags, text) in TRACE_DIFF.items():
        write("trace_diff", name, bytes([flags]) + text.encode())
    for name in ("exact_walk.jsonl", "super_naive.jsonl"):
        ours = os.path.join(CORPUS, "trace", name)
        if os.path.exists(ours):
            with open(ours, "rb") as f:
                write("trace_diff", "ours_" + name, bytes([2]) + f.read())
    for name, text in SETTINGS.items():
        write("settings", name, text)
    for target, (name, text) in DEEP_BAD.items():
        write(target, name, text)
    for name, data in engine_seeds().items():
        write("engine", name, data)
    if args.dtlab:
        trace_seeds(args.dtlab)


if __name__ == "__main__":
    main()
