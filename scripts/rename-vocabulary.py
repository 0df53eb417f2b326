#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Applies docs/vocabulary.md's renames to a cellforge tree, idempotently.

    python3 scripts/rename-vocabulary.py [ROOT]      (ROOT: the repository, default: this one)

Every renamed public name gets its new name everywhere (include/, tests/, examples/, bench/,
docs/, README.md; CHANGELOG.md is history and is left alone) plus one deprecated spelling of
the old name next to the new definition, removed in 0.8:
  types      `using old [[deprecated("use new; removed in 0.8")]] = new;`
  functions  a `[[deprecated("use new; removed in 0.8")]]` forwarder
  headers    the old path includes the new one and says so in a `#pragma message`
Running it again changes nothing, so after `git rebase main` the mechanical commit can be
dropped and made again from the rebased tree (other branches keep editing the same files).
"""

import re
import subprocess
import sys
from pathlib import Path

REMOVED_IN = "0.8"


def deprecated(new):
    return f'[[deprecated("use {new}; removed in {REMOVED_IN}")]]'


# old type -> (new type, template head of the alias or None, template arguments or None)
TYPES = {
    # <thing>_validation for checks
    "validation_result": ("mesh_validation", None, None),
    "cells_validation_result": ("cells_validation", None, None),
    "face_check": ("face_validation", None, None),
    "drawing_check_options": ("drawing_validation_options", None, None),
    # part-prefixed (or algorithm-named) options and results in the flat namespace
    "read_options": ("wireframe_read_options", None, None),
    "read_result": ("wireframe_read_result", None, None),
    "unique_options": ("unique_circuits_options", None, None),
    "unique_result": ("unique_circuits_result", None, None),
    "loop_options": ("loop_subdivision_options", None, None),
    "loop_result": ("loop_subdivision_result", None, None),
    "detection_options": ("thin_detection_options", None, None),
    "detection_result": ("thin_detection_result", None, None),
    # the part's name, as in tubes_result
    "tube_options": ("tubes_options", None, None),
}

# old function -> (new name, regex of the new definition's first line, forwarder text)
FUNCTIONS = {
    "validate_skeleton": (
        "validate",
        r"^skeleton_validation validate\(const G& g\) \{$",
        "/// Deprecated spelling of validate(g).\n"
        "template <Skeleton G>\n"
        f'{deprecated("validate(g)")} skeleton_validation validate_skeleton(const G& g) {{\n'
        "  return validate(g);\n"
        "}\n",
    ),
    "validate_drawing": (
        "validate",
        r"^drawing_validation validate\(const D& d, const drawing_validation_options& options = \{\}\) \{$",
        "/// Deprecated spelling of validate(d, options).\n"
        "template <LineDrawing D>\n"
        f'{deprecated("validate(d, options)")} drawing_validation\n'
        "validate_drawing(const D& d, const drawing_validation_options& options = {}) {\n"
        "  return validate(d, options);\n"
        "}\n",
    ),
    "validate_arcs": (
        "validate",
        r"^arc_validation validate\(const arc_drawing<P>& d, const drawing_validation_options& options = \{\}\) \{$",
        "/// Deprecated spelling of validate(d, options).\n"
        "template <Point2 P>\n"
        f'{deprecated("validate(d, options)")} arc_validation\n'
        "validate_arcs(const arc_drawing<P>& d, const drawing_validation_options& options = {}) {\n"
        "  return validate(d, options);\n"
        "}\n",
    ),
}

# how prose (comments, messages, docs) names the overload that replaced a function
PROSE = {"validate_skeleton": "validate(skeleton)", "validate_drawing": "validate(drawing)",
         "validate_arcs": "validate(arc_drawing)"}

# old header -> new header (paths under include/)
HEADERS = {
    # reads like svg_drawing.hpp (the reader); it writes pictures of drawings
    "cellforge/io/drawing_svg.hpp": "cellforge/io/drawing_pictures.hpp",
}

SCAN = ["include", "tests", "examples", "bench", "docs", "README.md", "cmake", "CMakeLists.txt"]
SUFFIXES = {".hpp", ".cpp", ".h", ".md", ".txt", ".cmake", ".py", ".sh", ".json", ".in"}
SKIP = {"CHANGELOG.md", "scripts/rename-vocabulary.py", "tests/deprecated/deprecated_names.cpp",
        "tests/compile_fail/deprecated_name.cpp"}


def tracked_files(root):
    out = subprocess.run(["git", "ls-files", "-z", "--", *SCAN], cwd=root, check=True,
                         capture_output=True).stdout.decode()
    for name in out.split("\0"):
        if not name or name in SKIP or name.startswith("bench/results/"):  # dated runs are history
            continue
        p = root / name
        if p.suffix in SUFFIXES and p.is_file():
            yield name, p


def is_forwarder(text):
    return "\n#pragma message" in text


def move_headers(root):
    for old, new in HEADERS.items():
        po, pn = root / "include" / old, root / "include" / new
        if pn.exists():
            continue  # moved already
        subprocess.run(["git", "mv", str(po), str(pn)], cwd=root, check=True)
        stem = Path(new).name
        po.write_text(
            "// SPDX-License-Identifier: MIT\n#pragma once\n/// \\file\n"
            f"/// Deprecated, removed in {REMOVED_IN}: this header is `{new}` now (same names); it\n"
            "/// includes it until then.\n\n"
            f'#include "{new}"\n\n'
            f'#pragma message("{old} is deprecated: include {new}")\n')
        subprocess.run(["git", "add", str(po)], cwd=root, check=True)
        print(f"moved {old} -> {new} ({stem})")


def rename_text(text, name):
    original = text
    for old, new in HEADERS.items():
        text = text.replace(old, new)
        # docs name headers without the cellforge/ prefix
        text = re.sub(r"(?<![\w/])" + re.escape(old.removeprefix("cellforge/")) + r"\b",
                      new.removeprefix("cellforge/"), text)
    lines = text.split("\n")
    in_forwarder = False
    for i, line in enumerate(lines):
        if line.startswith("/// Deprecated spelling of"):
            in_forwarder = True
        if in_forwarder:
            in_forwarder = line != "}"
            continue  # a forwarder keeps the old name
        if "[[deprecated(" in line or line.startswith("#pragma message"):
            continue  # the deprecated spellings keep the old names
        for old, (new, _, _) in TYPES.items():
            line = re.sub(r"\b" + old + r"\b", new, line)
        for old, (new, _, _) in FUNCTIONS.items():
            # a call or declaration takes the overload; prose names the overload by its input
            line = re.sub(r"\b" + old + r"(?=\s*\()", new, line)
            line = re.sub(r"\b" + old + r"\b", PROSE[old], line)
        lines[i] = line
    text = "\n".join(lines)
    return text, text != original


def block_end(lines, start):
    """Index of the line that closes the brace block opened at or after lines[start]."""
    depth, opened = 0, False
    for i in range(start, len(lines)):
        code = re.sub(r'"(\\.|[^"\\])*"', '""', lines[i].split("//")[0])
        for ch in code:
            if ch == "{":
                depth += 1
                opened = True
            elif ch == "}":
                depth -= 1
        if opened and depth == 0:
            return i
    raise SystemExit(f"unbalanced braces from line {start + 1}")


def add_type_aliases(text, name):
    lines = text.split("\n")
    changed = False
    for old, (new, head, args) in TYPES.items():
        if re.search(r"\busing " + old + r" \[\[deprecated", text):
            continue
        for i, line in enumerate(lines):
            if re.match(r"^struct " + new + r"\b", line) and not line.endswith(";"):
                end = block_end(lines, i)
            elif re.match(r"^struct " + new + r"\b.*\};$", line):
                end = i  # a one-line struct
            else:
                continue
            lines.insert(end + 1, f"using {old} {deprecated(new)} = {new};")
            changed = True
            print(f"{name}: alias {old}")
            break
    return "\n".join(lines), changed


def add_function_forwarders(text, name):
    lines = text.split("\n")
    changed = False
    for old, (new, signature, forwarder) in FUNCTIONS.items():
        if re.search(r"\b" + old + r"\(\s*const", text):
            continue
        for i, line in enumerate(lines):
            if re.match(signature, line):
                end = block_end(lines, i)
                lines[end + 1:end + 1] = [""] + forwarder.rstrip("\n").split("\n")
                changed = True
                print(f"{name}: forwarder {old}")
                break
    return "\n".join(lines), changed


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent).resolve()
    move_headers(root)
    formatted = []
    for name, path in tracked_files(root):
        text = path.read_text()
        if is_forwarder(text) and name.startswith("include/"):
            continue
        text, c1 = rename_text(text, name)
        c2 = c3 = False
        if name.startswith("include/"):
            text, c2 = add_type_aliases(text, name)
            text, c3 = add_function_forwarders(text, name)
        if c1 or c2 or c3:
            path.write_text(text)
            if path.suffix in {".hpp", ".cpp", ".h"}:
                formatted.append(name)
    # every alias and forwarder must have found its definition
    everything = "\n".join(p.read_text() for n, p in tracked_files(root) if n.startswith("include/"))
    missing = [o for o in TYPES if not re.search(r"\busing " + o + r" \[\[deprecated", everything)]
    missing += [o for o in FUNCTIONS if not re.search(r"\b" + o + r"\(\s*const", everything)]
    if missing:
        raise SystemExit("no definition found for: " + ", ".join(missing))
    # Format the C++ files this rename touched (run on a clean tree: those git sees changed), not
    # the others, which stay as their authors left them.
    changed = subprocess.run(["git", "diff", "--name-only", "HEAD"], cwd=root, check=True,
                             capture_output=True, text=True).stdout.split()
    cxx = [n for n in changed if Path(n).suffix in {".hpp", ".cpp", ".h"} and (root / n).is_file()]
    if cxx:
        subprocess.run(["clang-format-14", "-i", *cxx], cwd=root, check=True)
    print(f"{len(formatted)} files renamed now; {len(cxx)} changed C++ files formatted")


if __name__ == "__main__":
    main()
