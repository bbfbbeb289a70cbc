#!/usr/bin/env python3
"""No shader reinterprets the bits of data fetched through a float view as integers.

usage: check_shader_bit_casts.py [--expect N] PATH...

PATHs are shader files or folders of them (.glsl, .comp, .vert, .frag). An integer stored in a
buffer and read through a float texel view (samplerBuffer, RGBA32F) arrives as a float whose
bits are the integer's: for small integers a denormal, which GLSL lets a driver flush to zero
on the way (AMD and Intel do), so floatBitsToInt(texelFetch(float_view, i)) reads 0 there and
the integer's bits only on drivers that keep denormals (llvmpipe, NVIDIA). Integers must come
through an integer view (isamplerBuffer, usamplerBuffer) or a storage buffer instead.

Reports file:line for every floatBitsToInt / floatBitsToUint whose argument is fetched through a
float sampler or image: directly (texelFetch, texture, imageLoad), through a one-line accessor or
macro that returns such a fetch (position_of(i)), or through a local variable initialised from
one. Float samplers are collected over all PATHs together, since they are declared in included
files. Exit 1 on findings; with --expect N, exit 0 exactly when there are N (the test that the
scan finds what it is meant to, on tests/shaders/float_view_bit_cast.comp).
"""
import pathlib
import re
import sys

EXTENSIONS = {".glsl", ".comp", ".vert", ".frag"}


def strip_comments(text):
    # Keeps the newlines, so that offsets still give line numbers.
    text = re.sub(r"/\*.*?\*/", lambda m: re.sub(r"[^\n]", " ", m.group(0)), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def balanced_argument(text, open_paren):
    depth = 0
    for k in range(open_paren, len(text)):
        if text[k] == "(":
            depth += 1
        elif text[k] == ")":
            depth -= 1
            if depth == 0:
                return text[open_paren + 1:k]
    return text[open_paren + 1:]


def fetch_pattern(names):
    alternatives = "|".join(sorted(map(re.escape, names))) or r"(?!)"
    return re.compile(r"\b(?:texelFetch|texelFetchOffset|texture\w*|imageLoad)\s*\(\s*(?:" + alternatives +
                      r")\b|\b(?:" + alternatives + r")\s*\(")


def main(argv):
    expect = None
    if len(argv) >= 2 and argv[0] == "--expect":
        expect, argv = int(argv[1]), argv[2:]
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    files = []
    for p in map(pathlib.Path, argv):
        files += sorted(f for f in p.rglob("*") if f.suffix in EXTENSIONS) if p.is_dir() else [p]
    sources = {f: strip_comments(f.read_text()) for f in files}
    everything = "\n".join(sources.values())

    # Float samplers and images (no i/u prefix), then the accessors and macros that return a fetch
    # through one, to a fixed point (an accessor may call another).
    samplers = set(re.findall(r"\buniform\s+(?:(?:highp|mediump|lowp)\s+)?(?:sampler|image)\w*\s+(\w+)", everything))
    accessors = set()
    while True:
        fetch = fetch_pattern(samplers | accessors)
        found = {m.group(1) for m in re.finditer(r"\b\w+\s+(\w+)\s*\([^)]*\)\s*\{\s*return\s+([^;]*);", everything)
                 if fetch.search(m.group(2))}
        found |= {m.group(1) for m in re.finditer(r"#define\s+(\w+)\([^)]*\)([^\n]*)", everything)
                  if fetch.search(m.group(2))}
        if found <= accessors:
            break
        accessors |= found
    fetch = fetch_pattern(samplers | accessors)

    findings = []
    for f, text in sources.items():
        # Locals of this file initialised from a float fetch (vec4 r = texelFetch(float_view, i)).
        fetched = {m.group(1) for m in re.finditer(r"\b(?:float|vec[234])\s+(\w+)\s*=\s*([^;,]*)", text)
                   if fetch.search(m.group(2))}
        local = re.compile(r"\b(?:" + "|".join(map(re.escape, sorted(fetched))) + r")\b") if fetched else None
        for m in re.finditer(r"\bfloatBitsTo(?:Int|Uint)\s*\(", text):
            arg = balanced_argument(text, m.end() - 1)
            if fetch.search(arg) or (local and local.search(arg)):
                line = text.count("\n", 0, m.start()) + 1
                findings.append(f"{f}:{line}: {m.group(0).rstrip('( ')} of data fetched through a float view "
                                f"({arg.strip()}): a driver may flush it (a denormal) to zero; read integers "
                                "through an integer view (isamplerBuffer, usamplerBuffer) or a storage buffer")
    for line in findings:
        print(line)
    if expect is not None:
        print(f"{len(findings)} findings, expected {expect}")
        return 0 if len(findings) == expect else 1
    print(f"{len(files)} shader files, {len(samplers)} float samplers and images, {len(accessors)} accessors: "
          f"{len(findings)} bit casts of float fetches")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
