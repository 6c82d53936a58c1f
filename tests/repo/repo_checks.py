#!/usr/bin/env python3
"""Checks on the repository itself, not on the code: what a clone ships must stand alone.

  repo_checks.py no_outside_paths SOURCE_DIR
      No tracked file except .ci/run names the team's folder beside the repository (the
      parent folder's `shared`, or its reference folder; the patterns are OUTSIDE below): a
      user's clone does not have it.
  repo_checks.py doc_links SOURCE_DIR
      Every relative link in a tracked Markdown file points at a file or folder that exists,
      and a link to a heading (#anchor) at a heading that exists.
  repo_checks.py code_paths SOURCE_DIR
      Every path of the repository's own that a tracked Markdown file names (a source file,
      a script, an example: `servo/src/plant_factory.cpp`, `examples/nodes/x.yaml`) exists,
      so that the docs follow the code when files move. Files a recipe asks the reader to
      create (`my_*`), patterns (`*`, `<...>`, `...`), output folders and docs/migration.md's
      old names are not paths of the repository's.
  repo_checks.py readme_example SOURCE_DIR RPSD
      The README's worked example scenario (its first ```yaml block) passes `rpsd validate`,
      read from a folder where the repository's examples/ and data/ are at hand.

Every problem is printed; the exit code is 1 if there was any."""
import os
import re
import subprocess
import sys
import tempfile

# Spelt in two pieces so that this file does not name what it looks for.
OUTSIDE = [b".." + b"/shared", b"shared" + b"/reference"]
EXEMPT = {".ci/run"}


def tracked_files(source):
    try:
        out = subprocess.run(["git", "-C", source, "ls-files", "-z"], check=True, stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL).stdout
        names = [n.decode() for n in out.split(b"\0") if n]
    except (OSError, subprocess.CalledProcessError):
        # Not a git checkout (an unpacked archive): every file but build output.
        names = []
        for root, dirs, files in os.walk(source):
            dirs[:] = [d for d in dirs if d != ".git" and not d.startswith("build")]
            names += [os.path.relpath(os.path.join(root, f), source) for f in files]
    return sorted(n for n in names if os.path.isfile(os.path.join(source, n)))


def no_outside_paths(source):
    problems = []
    for name in tracked_files(source):
        if name in EXEMPT:
            continue
        with open(os.path.join(source, name), "rb") as f:
            for number, line in enumerate(f, 1):
                if any(p in line for p in OUTSIDE):
                    problems.append(f"{name}:{number}: names a folder outside the repository: "
                                    f"{line.decode(errors='replace').strip()}")
    return problems


FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_CODE = re.compile(r"`+[^`]*`+")
LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")


def prose_lines(text):
    """The lines outside fenced code blocks, with inline code removed."""
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, INLINE_CODE.sub("", line)


def anchors(path):
    """GitHub's anchors for the headings of a Markdown file."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    seen, result = {}, set()
    for _, line in prose_lines(text):
        m = HEADING.match(line)
        if not m:
            continue
        slug = re.sub(r"[^\w\- ]", "", m.group(2).strip().lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        result.add(slug if n == 0 else f"{slug}-{n}")
    return result


def doc_links(source):
    problems = []
    for name in tracked_files(source):
        if not name.endswith(".md"):
            continue
        path = os.path.join(source, name)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for number, line in prose_lines(text):
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # https:, mailto: ...
                    continue
                file_part, _, anchor = target.partition("#")
                linked = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                where = f"{name}:{number}: ({target})"
                if not os.path.exists(linked):
                    problems.append(f"{where}: no such file")
                elif not os.path.realpath(linked).startswith(os.path.realpath(source) + os.sep):
                    problems.append(f"{where}: points outside the repository")
                elif anchor and linked.endswith(".md") and anchor not in anchors(linked):
                    problems.append(f"{where}: no heading with anchor #{anchor}")
    return problems


CODE_PATH = re.compile(r"(?<![\w./-])((?:[A-Za-z0-9_.-]+/)+[A-Za-z0-9_.-]+\.(?:h|cpp|py|sh|yaml|yml|cmake|xml|tcl|"
                       r"json|idl|txt|AT2|md))(?![\w/])")
GENERATED = ("build", "results", "bench/results")
NOT_CHECKED = {"docs/migration.md"}


def spellings(path):
    """A path as written, and the docs' short form of a module's file: `servo/pid_controller.h`
    for servo/include/rpsd/servo/pid_controller.h, `servo/plant_factory.cpp` for
    servo/src/plant_factory.cpp."""
    module, _, rest = path.partition("/")
    yield path
    yield f"{module}/include/rpsd/{module}/{rest}"
    yield f"{module}/src/{rest}"


def code_paths(source):
    problems = []
    names = tracked_files(source)
    top = {n.split("/", 1)[0] for n in names if "/" in n}
    for name in names:
        if not name.endswith(".md") or name in NOT_CHECKED:
            continue
        with open(os.path.join(source, name), encoding="utf-8") as f:
            lines = f.read().splitlines()
        for number, line in enumerate(lines, 1):
            for path in CODE_PATH.findall(line):
                first = path.split("/", 1)[0]
                if first not in top or path.startswith(GENERATED) or "/my_" in path or path.split("/")[-1].startswith("my_"):
                    continue
                if not any(os.path.exists(os.path.join(source, p)) for p in spellings(path)):
                    problems.append(f"{name}:{number}: names {path}, which does not exist")
    return problems


def readme_example(source, rpsd):
    with open(os.path.join(source, "README.md"), encoding="utf-8") as f:
        blocks = re.findall(r"^```yaml\n(.*?)^```", f.read(), re.S | re.M)
    if not blocks:
        return ["README.md has no ```yaml block"]
    with tempfile.TemporaryDirectory() as folder:
        for shared in ("examples", "data", "transport"):
            os.symlink(os.path.join(os.path.abspath(source), shared), os.path.join(folder, shared))
        scenario = os.path.join(folder, "my-test.yaml")
        with open(scenario, "w", encoding="utf-8") as f:
            f.write(blocks[0])
        run = subprocess.run([rpsd, "validate", scenario], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             text=True, timeout=120)
        print(run.stdout)
        if run.returncode != 0:
            return [f"rpsd validate of the README's example: exit {run.returncode}"]
    return []


# A type a file or a caller fills in ends in the suffix of its role (docs/architecture.md, House
# style): Parameters, Config, Options or Setup; a deprecated alias keeps an old name.
OTHER_SUFFIX = re.compile(r"\b(?:struct|class|using)\s+([A-Z]\w*(?:Params|Settings|Spec|Conf|Cfg|Opts|Args))\b(?!\s*\[\[deprecated)")
KIND_LIST = re.compile(r"using\s+(\w+)\s*=\s*(?:config::)?KindList<([^>]*)>")


def type_suffixes(source):
    problems = []
    for name in tracked_files(source):
        if not name.endswith((".h", ".cpp")):
            continue
        with open(os.path.join(source, name), encoding="utf-8") as f:
            text = f.read()
        for number, line in enumerate(text.splitlines(), 1):
            for match in OTHER_SUFFIX.finditer(line):
                problems.append(f"{name}:{number}: {match.group(1)} ends in none of the roles' suffixes")
        for match in KIND_LIST.finditer(text):
            # A list's entry is a kind's values (…Parameters), or a kind that builds its part
            # itself, named by the list's noun: SiteKinds' DdsSite, DampingModels' ModalModel.
            line = text[text.rfind("\n", 0, match.start()) + 1:match.start()]
            if line.lstrip().startswith("//") or "..." in match.group(2):
                continue  # an example in a comment, or a template's own pack
            last_word = re.findall(r"[A-Z][a-z]*", match.group(1))[-1].removesuffix("s")
            nouns = ("Parameters", match.group(1).removesuffix("Kinds"), last_word)
            for entry in (e.strip() for e in match.group(2).split(",")):
                if re.fullmatch(r"[A-Z]\w*", entry) and not entry.endswith(nouns):
                    number = text.count("\n", 0, match.start()) + 1
                    problems.append(f"{name}:{number}: {entry} in {match.group(1)} ends in none of {nouns}")
    return problems


def production_names(source):
    """No source file outside tests/, bench/ and fuzz/ is named test_*: a test's name says a test."""
    return [f"{name}: a production file named test_*" for name in tracked_files(source)
            if name.endswith((".h", ".cpp")) and os.path.basename(name).startswith("test_")
            and name.split("/", 1)[0] not in ("tests", "bench", "fuzz")]


CASES = {"no_outside_paths": no_outside_paths, "doc_links": doc_links, "code_paths": code_paths,
         "readme_example": readme_example, "type_suffixes": type_suffixes,
         "production_names": production_names}

if __name__ == "__main__":
    case, *args = sys.argv[1:]
    problems = CASES[case](*args)
    for p in problems:
        print("FAILED:", p)
    print(f"{case}: {len(problems)} problem(s)")
    sys.exit(1 if problems else 0)
