#!/usr/bin/env python3
"""Writes each code block of CONTRIBUTING.md marked `<!-- recipe: NAME -->` to OUT/NAME.inc,
dedented, so that recipes_test.cpp compiles the recipes exactly as written.

usage: extract_recipes.py CONTRIBUTING.md OUT NAME...   (fails when a NAME has no block)
"""
import pathlib
import re
import sys


def recipes(text):
    found = {}
    pattern = re.compile(r"^([ \t]*)<!-- recipe: (\w+) -->\n\1```cpp\n(.*?)^\1```$", re.M | re.S)
    for match in pattern.finditer(text):
        indent, name, body = match.group(1), match.group(2), match.group(3)
        lines = [line[len(indent):] if line.startswith(indent) else line.lstrip() for line in body.splitlines()]
        found[name] = "\n".join(lines) + "\n"
    return found


def main():
    source, out, names = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3:]
    found = recipes(source.read_text())
    missing = [n for n in names if n not in found]
    if missing:
        sys.exit(f"{source}: no recipe block for {', '.join(missing)} (<!-- recipe: NAME --> before ```cpp)")
    out.mkdir(parents=True, exist_ok=True)
    for name in names:
        target = out / f"{name}.inc"
        text = f"// Generated from {source.name} by extract_recipes.py: edit the recipe there.\n" + found[name]
        if not target.exists() or target.read_text() != text:
            target.write_text(text)


if __name__ == "__main__":
    main()
