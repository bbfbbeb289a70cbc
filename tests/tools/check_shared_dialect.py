#!/usr/bin/env python3
"""The files of compute/shared/ use only what GLSL and C++ both compile and mean alike.

usage: check_shared_dialect.py [--expect N] [--calls CPP] PATH...

PATHs are .glsl files or folders of them (dialect.glsl, which defines the dialect, is left
out). Each file is compiled as GLSL by the shaders and as C++ by the CPU reference
(compute/shared/dialect.glsl says how), so outside `#ifdef __cplusplus` blocks (and their
`#else`) it must not use:
  - a floating literal not written REAL(...) (C++ would compute a float formula in double);
  - a type or qualifier of one language: float, double, vecN, ivecN, in, out, inout, precise,
    const, auto, template, ::, -> (REAL, VEC3, VEC4, INOUT(T), OUT(T), PRECISE instead);
  - switch, arrays, swizzles of two or more components (.xyz), or % (undefined for negative
    operands in GLSL);
  - a call to anything but the built-ins the dialect brings into C++ (sqrt, floor, ceil, abs,
    min, max, floatBitsToUint, uintBitsToFloat), the dialect's own (nonzero3, F32, the type constructors) and the functions the
    shared files define;
  - a function without SHARED_FN or SHARED_FN_INLINE (or SHARED for integer ones) in front.
With --calls CPP, also that every SHARED_FN function is called in the C++ file CPP (the test
that compiles them for float and double with -Werror -Wconversion -Wdouble-promotion), so none
escapes that compile. Exit 1 on findings; with --expect N, exit 0 exactly when there are N (the
check of this script on tests/tools/shared_dialect_bad.glsl).
"""
import pathlib
import re
import sys

BUILTINS = {"sqrt", "floor", "ceil", "abs", "min", "max", "floatBitsToUint", "uintBitsToFloat"}
DIALECT = {"nonzero3", "F32", "REAL", "VEC3", "VEC4", "SYM3", "INOUT", "OUT", "int", "uint", "bool"}
KEYWORDS = {"if", "for", "while", "return", "defined", "sizeof", "switch", "case", "else", "do"}
FORBIDDEN_WORDS = [
    "float", "double", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "uvec2", "uvec3", "uvec4",
    "bvec2", "bvec3", "bvec4", "dvec3", "in", "out", "inout", "precise", "const", "auto", "template",
    "switch", "case", "static_cast", "std",
]
FLOAT_LITERAL = re.compile(r"(?<![\w.])(\d+\.\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?|\d+[eE][-+]?\d+)[fFlL]?(?![\w.])")
WRAPPED_LITERAL = re.compile(r"REAL\(\s*-?\s*$")
DEFINITION = re.compile(r"^(?P<prefix>[^\n;{}()]*?)\b(?P<name>\w+)\s*\((?P<args>[^;{}]*)\)\s*\{", re.M)


def strip_comments(text):
    # Keeps the newlines, so that offsets still give line numbers.
    text = re.sub(r"/\*.*?\*/", lambda m: re.sub(r"[^\n]", " ", m.group(0)), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def shared_part(text):
    """The text both languages compile: preprocessor lines and `#ifdef __cplusplus` blocks
    (both branches) blanked, newlines kept."""
    out, stack = [], []
    for line in text.split("\n"):
        d = line.strip()
        language = False
        if re.match(r"#\s*(if|ifdef|ifndef)\b", d):
            stack.append("__cplusplus" in d)
            language = True
        elif re.match(r"#\s*(else|elif)\b", d):
            language = True
        elif re.match(r"#\s*endif\b", d):
            if stack:
                stack.pop()
            language = True
        elif d.startswith("#"):
            language = True
        out.append("" if language or any(stack) else line)
    return "\n".join(out)


def defined_functions(text):
    return {m.group("name") for m in DEFINITION.finditer(text) if m.group("name") not in KEYWORDS}


def check_file(path, known, findings):
    raw = strip_comments(path.read_text())
    text = shared_part(raw)

    def report(offset, what):
        findings.append(f"{path}:{text.count(chr(10), 0, offset) + 1}: {what}")

    for m in FLOAT_LITERAL.finditer(text):
        if not WRAPPED_LITERAL.search(text[max(0, m.start() - 12):m.start()]):
            report(m.start(), f"floating literal {m.group(0)} not written REAL({m.group(0)})")
    for word in FORBIDDEN_WORDS:
        for m in re.finditer(rf"(?<![\w.]){word}\b", text):
            report(m.start(), f"'{word}' is one language's; use the dialect (compute/shared/dialect.glsl)")
    for m in re.finditer(r"::|->", text):
        report(m.start(), f"'{m.group(0)}' is C++ only")
    for m in re.finditer(r"\w\s*\[", text):
        report(m.start(), "an array: GLSL's and C++'s differ")
    for m in re.finditer(r"\.([xyzw]{2,4}|[rgba]{2,4}|[stpq]{2,4})\b", text):
        report(m.start(), f"swizzle .{m.group(1)}: C++ (glm) has none")
    for m in re.finditer(r"%", text):
        report(m.start(), "% differs between the languages for negative operands")
    for m in re.finditer(r"(?<![\w.])(\w+)\s*\(", text):
        name = m.group(1)
        if name in BUILTINS or name in DIALECT or name in KEYWORDS or name in known:
            continue
        report(m.start(), f"{name}(...) is not a function of the dialect nor of compute/shared/")
    for m in DEFINITION.finditer(text):
        if m.group("name") in KEYWORDS:
            continue
        if not re.search(r"\bSHARED(_FN(_INLINE)?)?\b", m.group("prefix")):
            report(m.start("name"), f"function {m.group('name')} without SHARED_FN (or SHARED) in front")


def main(argv):
    expect, calls = None, None
    while argv and argv[0] in ("--expect", "--calls"):
        if argv[0] == "--expect":
            expect = int(argv[1])
        else:
            calls = pathlib.Path(argv[1])
        argv = argv[2:]
    files = []
    for a in argv:
        p = pathlib.Path(a)
        files += sorted(p.glob("*.glsl")) if p.is_dir() else [p]
    files = [f for f in files if f.name != "dialect.glsl"]
    if not files:
        print("no shared files found")
        return 1
    texts = {f: strip_comments(f.read_text()) for f in files}
    known = set()
    for t in texts.values():
        known |= defined_functions(t)
    findings = []
    for f in files:
        check_file(f, known, findings)
    if calls is not None:
        called = set(re.findall(r"\b(\w+)\s*\(", strip_comments(calls.read_text())))
        for f, t in texts.items():
            for m in re.finditer(r"SHARED_FN(?:_INLINE)?\s+[\w<>]+\s+(\w+)\s*\(", t):
                if m.group(1) not in called:
                    findings.append(f"{f}: {m.group(1)} is not called in {calls}, so no strict compile checks it")
    for line in findings:
        print(line)
    if expect is not None:
        print(f"{len(findings)} findings, expected {expect}")
        return 0 if len(findings) == expect else 1
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
