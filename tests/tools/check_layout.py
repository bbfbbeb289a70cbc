#!/usr/bin/env python3
"""The code layout's rules (docs/code-layout.md), checked on the sources as committed:

1. host/core is a folder per concern, each using only the folders before it in LAYERS (an
   include that runs back up, or out of host/core into GL or the app, is refused);
2. no source file is over MAX_LINES lines;
3. no function in the step's path (the reference step, the GPU simulator, the compute shaders)
   is over MAX_FUNCTION_LINES lines.

Usage: check_layout.py REPOSITORY_ROOT. Prints each breach and exits 1 if there is one.
check_layout.py --self-test builds a small tree with one breach of each rule and exits 0 only
if exactly those are found (so the check itself can be seen to fail).
"""
import pathlib
import re
import sys

LAYERS = ["io", "scene", "cloth", "colliders", "reference", "analysis", "export"]
MAX_LINES = 350
MAX_FUNCTION_LINES = 80
SOURCE_SUFFIXES = {".cpp", ".hpp", ".h", ".glsl", ".comp", ".vert", ".frag", ".py", ".sh"}
SOURCE_FOLDERS = ["host", "compute", "shaders", "tests", "tools", "scripts", "python"]
STEP_PATH = ["host/core/reference", "host/gpu", "compute"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def layer_of(path: pathlib.Path, core: pathlib.Path):
    """The layer index of a file under host/core (len(LAYERS) for backend.hpp at its top)."""
    rel = path.relative_to(core)
    if len(rel.parts) == 1:
        return len(LAYERS)
    return LAYERS.index(rel.parts[0]) if rel.parts[0] in LAYERS else None


def check_layers(root: pathlib.Path, problems: list):
    core = root / "host" / "core"
    for f in sorted(core.rglob("*")):
        if f.suffix not in {".cpp", ".hpp"}:
            continue
        mine = layer_of(f, core)
        if mine is None:
            problems.append(f"{f.relative_to(root)}: in no folder of the layers {LAYERS}")
            continue
        text = f.read_text()
        for m in INCLUDE.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            name = m.group(1)
            target = (f.parent / name) if (f.parent / name).exists() else core / name
            target = target.resolve()
            where = f"{f.relative_to(root)}:{line}"
            if not target.exists():
                problems.append(f"{where}: includes {name}, which is not in host/core")
                continue
            try:
                theirs = layer_of(target, core.resolve())
            except ValueError:
                # Outside host/core: only the shaders' shared layout and formulas may be used.
                rel = target.relative_to(root.resolve())
                if rel.parts[0] != "compute":
                    problems.append(f"{where}: host/core includes {rel}, outside it and compute/")
                continue
            if theirs is not None and theirs > mine:
                problems.append(
                    f"{where}: {f.relative_to(core).parts[0]}/ includes {name}, "
                    f"a later layer: the arrow runs back up ({' < '.join(LAYERS)})")


def check_sizes(root: pathlib.Path, problems: list):
    for folder in SOURCE_FOLDERS:
        for f in sorted((root / folder).rglob("*")):
            if f.suffix in SOURCE_SUFFIXES and f.is_file():
                n = f.read_text(errors="replace").count("\n")
                if n > MAX_LINES:
                    problems.append(f"{f.relative_to(root)}: {n} lines, over {MAX_LINES}")


def strip_comments_and_strings(text: str) -> str:
    """Blanks comments and literals (keeping newlines) so that braces in them do not count."""
    out = re.sub(r"//[^\n]*", "", text)
    out = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), out, flags=re.S)
    out = re.sub(r'"(?:\\.|[^"\\\n])*"', '""', out)
    out = re.sub(r"'(?:\\.|[^'\\\n])*'", "''", out)
    return out


def functions(text: str):
    """(name, first line, lines) of every outermost function body in a C++ or GLSL file."""
    code = strip_comments_and_strings(text)
    depth_kinds = []  # per open brace: True if it opened a function body
    start = 0         # where the statement before the current brace began
    body_start = None
    name = None
    for i, ch in enumerate(code):
        if ch == "{":
            head = code[start:i]
            in_function = any(depth_kinds)
            is_function = (not in_function and ")" in head and
                           not re.search(r"\b(namespace|struct|class|enum|union)\b", head.split("(")[0]) and
                           not re.search(r"=\s*$", head.strip()))
            depth_kinds.append(is_function)
            if is_function:
                body_start = i
                m = re.search(r"([A-Za-z_][A-Za-z_0-9:<>~]*)\s*\(", head)
                name = m.group(1) if m else "?"
            start = i + 1
        elif ch == "}":
            if depth_kinds and depth_kinds.pop() and body_start is not None:
                first = code.count("\n", 0, body_start) + 1
                last = code.count("\n", 0, i) + 1
                yield name, first, last - first + 1
                body_start = None
            start = i + 1
        elif ch == ";":
            start = i + 1


def check_functions(root: pathlib.Path, problems: list):
    for folder in STEP_PATH:
        for f in sorted((root / folder).rglob("*")):
            if f.suffix not in SOURCE_SUFFIXES - {".py", ".sh"} or not f.is_file():
                continue
            for name, first, lines in functions(f.read_text()):
                if lines > MAX_FUNCTION_LINES:
                    problems.append(f"{f.relative_to(root)}:{first}: {name} is {lines} lines, "
                                    f"over {MAX_FUNCTION_LINES} (the step's path)")


def self_test() -> int:
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        root = pathlib.Path(d)
        (root / "host/core/io").mkdir(parents=True)
        (root / "host/core/scene").mkdir(parents=True)
        (root / "compute").mkdir()
        (root / "host/core/scene/scene.hpp").write_text("#pragma once\n")
        # io/ is below scene/: an include of it runs back up.
        (root / "host/core/io/input_file.cpp").write_text('#include "scene/scene.hpp"\n')
        (root / "host/core/io/long.cpp").write_text("// x\n" * (MAX_LINES + 1))
        body = "  x = x + 1.0;\n" * MAX_FUNCTION_LINES
        (root / "compute/pass.comp").write_text("void main() {\n" + body + "}\n")
        problems = []
        check_layers(root, problems)
        check_sizes(root, problems)
        check_functions(root, problems)
    expected = ["runs back up", f"over {MAX_LINES}", f"over {MAX_FUNCTION_LINES}"]
    found = [any(e in p for p in problems) for e in expected]
    print("\n".join(problems))
    if len(problems) != 3 or not all(found):
        print(f"check_layout --self-test: expected one breach of each rule, found {len(problems)}")
        return 1
    print("check_layout --self-test: each rule's breach was found")
    return 0


def main() -> int:
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    problems = []
    check_layers(root, problems)
    check_sizes(root, problems)
    check_functions(root, problems)
    for p in problems:
        print(p)
    if problems:
        print(f"check_layout: {len(problems)} breaches of docs/code-layout.md")
        return 1
    print("check_layout: host/core's layers, file sizes and the step's function sizes hold")
    return 0


if __name__ == "__main__":
    sys.exit(main())
