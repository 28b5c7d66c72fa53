#!/usr/bin/env python3
"""Holds docs/architecture.md's table of libraries against the tree and the build.

Fails, saying what differs, when
- a folder (or a file at the top) of libcam/ is in no row of the table, or in two, or a
  row names one that does not exist;
- a library the build defines (add_library(libcam::NAME ALIAS ...)) has no row, or a row
  names one the build does not define;
- a library links a libcam library that its row does not let it use (directly or
  through the libraries it uses), or its row names one it does not link;
- a file includes a libcam header of a library that its own library may not use, or, in
  a library of several folders (listed from the bottom), a header of a folder listed
  after its own: no layer includes one above it.

Usage: scripts/check-architecture.py [SOURCE_DIR]   (default: this script's repository)
"""

import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
DOC = ROOT / "docs" / "architecture.md"
SOURCES = ROOT / "libcam"
GENERATED = {"version"}  # libcam/version.hpp, made by the build (core's, cmake/version.hpp.in)


def expand(token):
    """libcam/{a,b} -> [a, b]; libcam/error.* -> [error]; libcam/io -> [io]."""
    token = token.removeprefix("libcam/").rstrip("/")
    braces = re.fullmatch(r"\{([^}]*)\}", token)
    names = braces.group(1).split(",") if braces else [token]
    return [name.strip().split(".")[0] for name in names]


def read_table():
    """The Libraries table: {library: (folders in order, libraries it uses)}."""
    section = DOC.read_text().split("\n## Libraries", 1)
    if len(section) < 2:
        sys.exit(f"check-architecture: {DOC.relative_to(ROOT)} has no '## Libraries' section")
    rows = {}
    for line in section[1].split("\n## ", 1)[0].splitlines():
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if not line.startswith("| `libcam::") or len(cells) < 3:
            continue
        library = cells[0].strip("`").removeprefix("libcam::")
        folders = [name for token in re.findall(r"`([^`]+)`", cells[1]) for name in expand(token)]
        uses = [] if cells[2] in ("", "-") else [name.strip().strip("`").removeprefix("libcam::")
                                                  for name in cells[2].split(",")]
        rows[library] = (folders, uses)
    if not rows:
        sys.exit(f"check-architecture: no row of libraries in {DOC.relative_to(ROOT)}'s table")
    return rows


def units_in_tree():
    """The folders of libcam/ and the stems of its top-level sources."""
    units = {path.name for path in SOURCES.iterdir() if path.is_dir()}
    units |= {path.stem for path in SOURCES.iterdir() if path.suffix in (".hpp", ".cpp")}
    return units


def targets_in_build():
    """{library: libcam libraries it links}, from the CMakeLists.txt files under libcam/."""
    targets = {}
    lists = [path.read_text() for path in sorted(SOURCES.rglob("CMakeLists.txt"))]
    for text in lists:
        for name, target in re.findall(r"add_library\(libcam::(\w+)\s+ALIAS\s+(\w+)\)", text):
            links = set()
            for other in lists:
                for body in re.findall(r"target_link_libraries\(\s*" + target + r"\b([^)]*)\)", other):
                    links |= set(re.findall(r"\blibcam_(\w+)", body)) - {"warnings"}
            targets[name] = links
    return targets


def closure(library, rows):
    seen, todo = set(), [library]
    while todo:
        for used in rows.get(todo.pop(), ((), ()))[1]:
            if used not in seen:
                seen.add(used)
                todo.append(used)
    return seen


def check():
    rows = read_table()
    problems = []
    owner = {}
    for library, (folders, _) in rows.items():
        for folder in folders:
            if folder in owner:
                problems.append(f"libcam/{folder} is in the rows of both libcam::{owner[folder]} and libcam::{library}")
            owner[folder] = library
    tree = units_in_tree()
    for unit in sorted(tree - owner.keys()):
        problems.append(f"libcam/{unit} is in the tree but in no row of the table")
    for unit in sorted(owner.keys() - tree):
        problems.append(f"libcam/{unit} is in libcam::{owner[unit]}'s row but not in the tree")

    targets = targets_in_build()
    for library in sorted(targets.keys() - rows.keys()):
        problems.append(f"libcam::{library} is built (add_library) but has no row in the table")
    for library in sorted(rows.keys() - targets.keys()):
        problems.append(f"libcam::{library} has a row in the table but the build defines no such library")
    for library, links in sorted(targets.items()):
        if library not in rows:
            continue
        allowed = closure(library, rows)
        for linked in sorted(links - allowed):
            problems.append(f"libcam::{library} links libcam::{linked}, which its row does not let it use")
        for used in sorted(set(rows[library][1]) - links):
            problems.append(f"libcam::{library}'s row uses libcam::{used}, which the build does not link")

    for path in sorted(SOURCES.rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".inl"):
            continue
        relative = path.relative_to(SOURCES)
        unit = relative.parts[0] if len(relative.parts) > 1 else path.stem
        library = owner.get(unit)
        if library is None:
            continue
        folders, _ = rows[library]
        allowed = closure(library, rows) | {library}
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            match = re.match(r'\s*#\s*include\s+"libcam/([^"]+)"', line)
            if not match:
                continue
            parts = match.group(1).split("/")
            target_unit = parts[0] if len(parts) > 1 else parts[0].split(".")[0]
            if target_unit in GENERATED:
                continue
            target_library = owner.get(target_unit)
            where = f"libcam/{relative}:{number}"
            if target_library is None:
                problems.append(f"{where} includes libcam/{match.group(1)}, in no library of the table")
            elif target_library not in allowed:
                problems.append(f"{where} (libcam::{library}) includes libcam/{match.group(1)} "
                                f"(libcam::{target_library}), which libcam::{library} may not use")
            elif target_library == library and folders.index(target_unit) > folders.index(unit):
                problems.append(f"{where} (libcam/{unit}) includes libcam/{match.group(1)}: a folder listed "
                                f"above its own in libcam::{library}'s row (listed from the bottom)")
    return problems


if __name__ == "__main__":
    found = check()
    for problem in found:
        print(f"check-architecture: {problem}")
    if found:
        print(f"check-architecture: {len(found)} difference(s) between {DOC.relative_to(ROOT)}'s table of "
              "libraries and the tree")
        sys.exit(1)
    print(f"check-architecture: {DOC.relative_to(ROOT)}'s table matches libcam/'s folders, the libraries the "
          "build defines and what each includes")
