#!/usr/bin/env python3
"""Check README.md and docs/ against the files and the program they describe.

- Every relative link and image (Markdown `[text](target)`, reference definitions, HTML
  `href`/`src`) must lead to an existing file or folder, and an `#anchor` into a Markdown
  file must name one of its headings: GitHub's heading ids for every file, and MkDocs' as
  well for files under docs/ (the site is built from there). MkDocs' own strict build does
  not see README.md, which lies outside its docs_dir.
- Every `garment-retarget COMMAND ...` line of a shell code block (also run through a
  path, such as `build/app/garment-retarget`; lines continued with a backslash are one
  command) must name a command the program has, and each `--option` it names must appear
  in `garment-retarget COMMAND --help`. A pattern such as `--binding-*` must match one.
- The folder table of docs/layout.md and the folder list of the README's "Where things
  live" name every top-level folder of the repository, in the same order, and each
  subfolder a row names (`stages/`) exists in it. The table's order is the dependency
  order: no C++ file includes (`#include "folder/..."`) from a folder listed after its own.

Prints one line per problem and exits with 1 if there is any, 0 otherwise.
Usage: tools/check_docs.py --binary build/app/garment-retarget [--root DIR]
"""

import argparse
import fnmatch
import os
import re
import shlex
import subprocess
import sys
import unicodedata
from urllib.parse import unquote

PROGRAM = "garment-retarget"
SHELL_LANGUAGES = {"", "sh", "bash", "shell", "console", "zsh"}

FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})\s*([\w+-]*)")
HEADING = re.compile(r"^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEFINITION = re.compile(r"^ {0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)", re.M)
HTML_LINK = re.compile(r"<(?:a|img)\b[^>]*?\b(?:href|src)\s*=\s*\"([^\"]+)\"", re.I)
INLINE_CODE = re.compile(r"(`+)(?:.+?)\1", re.S)
HELP_OPTION = re.compile(r"^  (?:-\w,\s?)?(--\w[\w-]*)")
HELP_SUBCOMMAND = re.compile(r"^  (\w[\w-]*)\s")
LAYOUT_ROW = re.compile(r"^\| `([\w.-]+)/` \|(.*)$", re.M)
README_FOLDER = re.compile(r"^- `([\w.-]+)/`:", re.M)
SUBFOLDER = re.compile(r"`([\w.-]+)/`")
PROJECT_INCLUDE = re.compile(r'^\s*#\s*include\s+"([\w.-]+)/', re.M)
SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc")
# Folders whose files may include from any other: the tests and the documentation.
UNRANKED = {"tests", "docs", "tools"}


def split_markdown(text):
    """The text with fenced code blocks blanked out (line numbers kept), and the blocks
    as (language, first line number, lines)."""
    prose, blocks = [], []
    fence, language, start, body = None, "", 0, []
    for number, line in enumerate(text.split("\n"), 1):
        match = FENCE.match(line)
        if fence is None and match:
            fence, language, start, body = match.group(1), match.group(2).lower(), number + 1, []
            prose.append("")
        elif fence is not None and line.strip().startswith(fence[0] * len(fence)) \
                and not line.strip().strip(fence[0]):
            blocks.append((language, start, body))
            fence = None
            prose.append("")
        elif fence is not None:
            body.append(line)
            prose.append("")
        else:
            prose.append(line)
    return "\n".join(prose), blocks


def heading_texts(prose):
    """Plain text of each ATX heading, as a renderer would show it."""
    texts = []
    for line in prose.split("\n"):
        match = HEADING.match(line)
        if not match:
            continue
        text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", match.group(2))  # links: their text
        text = re.sub(r"<[^>]+>", "", text)                                # HTML tags
        text = re.sub(r"(`+)(.+?)\1", r"\2", text)                         # code spans
        text = re.sub(r"(\*{1,3}|_{1,3})(\S(?:.*?\S)?)\1", r"\2", text)    # emphasis
        texts.append(text)
    return texts


def github_slug(text):
    slug = re.sub(r"[^\w\- ]", "", text.strip().lower())
    return slug.replace(" ", "-")


def mkdocs_slug(text):
    """Python-Markdown's toc slugify, as MkDocs uses it by default."""
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode("ascii")
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def anchors(texts, slugify, separator):
    """Heading ids with duplicates numbered as the renderer numbers them."""
    seen, ids = {}, set()
    for text in texts:
        slug = slugify(text)
        if slug in seen:
            seen[slug] += 1
            slug = f"{slug}{separator}{seen[slug]}"
        else:
            seen[slug] = 0
        ids.add(slug)
    return ids


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


class Checker:
    def __init__(self, root, binary):
        self.root = os.path.abspath(root)
        self.binary = binary
        self.docs = os.path.join(self.root, "docs")
        self.problems = []
        self.headings = {}
        self.helps = {}
        self.unavailable = set()
        self.links = 0
        self.commands = 0

    def problem(self, path, line, message):
        self.problems.append(f"{os.path.relpath(path, self.root)}:{line}: {message}")

    def markdown_files(self):
        files = [os.path.join(self.root, "README.md")]
        for folder, _, names in os.walk(self.docs):
            files += [os.path.join(folder, n) for n in sorted(names) if n.endswith(".md")]
        return [f for f in files if os.path.isfile(f)]

    def heading_ids(self, path):
        """(GitHub ids, MkDocs ids or None outside docs/) of a Markdown file."""
        if path not in self.headings:
            with open(path, encoding="utf-8") as f:
                texts = heading_texts(split_markdown(f.read())[0])
            in_docs = os.path.commonpath([path, self.docs]) == self.docs
            self.headings[path] = (anchors(texts, github_slug, "-"),
                                   anchors(texts, mkdocs_slug, "_") if in_docs else None)
        return self.headings[path]

    def check_link(self, path, line, target):
        self.links += 1
        if re.match(r"^[a-zA-Z][\w+.-]*:", target) or target.startswith("//"):
            return  # a URL with a scheme: not checked here
        address, _, anchor = target.partition("#")
        address = unquote(address.partition("?")[0])
        if not address:
            resolved = path
        elif address.startswith("/"):
            resolved = os.path.normpath(os.path.join(self.root, address.lstrip("/")))
        else:
            resolved = os.path.normpath(os.path.join(os.path.dirname(path), address))
        if not os.path.exists(resolved):
            self.problem(path, line, f"link '{target}': no such file "
                                     f"'{os.path.relpath(resolved, self.root)}'")
            return
        if os.path.commonpath([resolved, self.root]) != self.root:
            self.problem(path, line, f"link '{target}' leads outside the repository")
            return
        if not anchor or not resolved.endswith(".md"):
            return
        github, mkdocs = self.heading_ids(resolved)
        where = os.path.relpath(resolved, self.root)
        if anchor not in github:
            self.problem(path, line, f"link '{target}': no heading with GitHub id '{anchor}' in {where}")
        elif mkdocs is not None and anchor not in mkdocs:
            self.problem(path, line, f"link '{target}': no heading with MkDocs id '{anchor}' in {where}")

    def check_links(self, path, prose):
        text = INLINE_CODE.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), prose)
        for pattern in (INLINE_LINK, REFERENCE_DEFINITION, HTML_LINK):
            for match in pattern.finditer(text):
                self.check_link(path, line_of(text, match.start()), match.group(1))

    def help_text(self, command):
        """`--help` of a command (None: the program itself), or None when it cannot run."""
        if command not in self.helps:
            arguments = [self.binary] + ([command] if command else []) + ["--help"]
            try:
                run = subprocess.run(arguments, capture_output=True, text=True, timeout=60)
                self.helps[command] = run.stdout + run.stderr if run.returncode == 0 else None
            except (OSError, subprocess.SubprocessError):
                self.helps[command] = None
        return self.helps[command]

    def help_entries(self, command, section, pattern):
        text = self.help_text(command) or ""
        entries, inside = set(), False
        for line in text.split("\n"):
            if re.match(r"^\S.*:\s*$", line):
                inside = line.strip() == section
            elif inside:
                match = pattern.match(line)
                if match:
                    entries.add(match.group(1))
        return entries

    def cannot_run(self, path, line, command):
        """One problem per help text that could not be had, at its first use."""
        if command not in self.unavailable:
            self.unavailable.add(command)
            shown = f"{self.binary} {command}" if command else self.binary
            self.problem(path, line, f"cannot run '{shown} --help'")

    def check_command(self, path, line, tokens):
        self.commands += 1
        if self.help_text(None) is None:
            self.cannot_run(path, line, None)
            return
        command = tokens[0] if tokens and not tokens[0].startswith("-") else None
        if command is not None:
            if command not in self.help_entries(None, "Subcommands:", HELP_SUBCOMMAND):
                self.problem(path, line, f"'{PROGRAM} {command}': no such command")
                return
            if self.help_text(command) is None:
                self.cannot_run(path, line, command)
                return
            tokens = tokens[1:]
        known = self.help_entries(command, "Options:", HELP_OPTION)
        name = f"{PROGRAM} {command}" if command else PROGRAM
        for token in tokens:
            option = token.strip("[]()|,").partition("=")[0]
            if not option.startswith("--") or option == "--":
                continue
            if "*" in option:
                if not fnmatch.filter(known, option):
                    self.problem(path, line, f"'{name}': no option matches '{option}' in its --help")
            elif option not in known:
                self.problem(path, line, f"'{name}': no option '{option}' in its --help")

    def check_code(self, path, blocks):
        for language, start, body in blocks:
            if language not in SHELL_LANGUAGES:
                continue
            logical, first = "", None
            for number, text in enumerate(body, start):
                first = number if first is None else first
                if text.rstrip().endswith("\\"):
                    logical += text.rstrip()[:-1] + " "
                    continue
                self.check_shell_line(path, first, logical + text)
                logical, first = "", None
            if logical:
                self.check_shell_line(path, first, logical)

    def check_shell_line(self, path, line, text):
        try:
            tokens = shlex.split(text, comments=True)
        except ValueError:
            tokens = text.split("#", 1)[0].split()
        segment = []
        for token in tokens + [";"]:
            if token in ("&&", "||", ";") or token.endswith(";"):
                if token not in ("&&", "||", ";"):
                    segment.append(token[:-1])
                self.check_segment(path, line, segment)
                segment = []
            else:
                segment.append(token)

    def check_segment(self, path, line, tokens):
        for i, token in enumerate(tokens):
            if os.path.basename(token) == PROGRAM:
                if self.binary:
                    self.check_command(path, line, tokens[i + 1:])
                return

    def top_level_folders(self):
        """Folders at the repository's top that hold tracked files (all but hidden ones
        and build output when git is not there)."""
        try:
            listed = subprocess.run(["git", "-C", self.root, "ls-files"], capture_output=True,
                                    text=True, check=True).stdout.split("\n")
            return {path.split("/")[0] for path in listed if "/" in path and not path.startswith(".")}
        except (OSError, subprocess.CalledProcessError):
            return {name for name in os.listdir(self.root)
                    if os.path.isdir(os.path.join(self.root, name))
                    and not name.startswith((".", "build", "out", "site"))}

    def check_layout(self):
        layout = os.path.join(self.docs, "layout.md")
        readme = os.path.join(self.root, "README.md")
        if not os.path.isfile(layout):
            return
        with open(layout, encoding="utf-8") as f:
            rows = [(m.group(1), m.group(2), line_of(m.string, m.start())) for m in LAYOUT_ROW.finditer(f.read())]
        with open(readme, encoding="utf-8") as f:
            listed = README_FOLDER.findall(f.read())
        actual = self.top_level_folders()
        table = [name for name, _, _ in rows]
        for name in sorted(actual - set(table)):
            self.problem(layout, 1, f"the folder table does not name top-level folder {name}/")
        for name, text, line in rows:
            folder = os.path.join(self.root, name)
            if name not in actual:
                self.problem(layout, line, f"{name}/ is not a top-level folder")
                continue
            for sub in SUBFOLDER.findall(text):
                if not any(sub in dirs for _, dirs, _ in os.walk(folder)):
                    self.problem(layout, line, f"{name}/ has no subfolder {sub}/")
        if listed != table:
            self.problem(readme, 1, "the folders of 'Where things live' differ from docs/layout.md's table: "
                         f"{', '.join(listed)} against {', '.join(table)}")
        self.check_includes([name for name in table if name not in UNRANKED])

    def check_includes(self, ranked):
        rank = {name: i for i, name in enumerate(ranked)}
        for name in ranked:
            for folder, _, names in os.walk(os.path.join(self.root, name)):
                for source in sorted(n for n in names if n.endswith(SOURCE_SUFFIXES)):
                    path = os.path.join(folder, source)
                    with open(path, encoding="utf-8", errors="replace") as f:
                        text = f.read()
                    for match in PROJECT_INCLUDE.finditer(text):
                        target = match.group(1)
                        if rank.get(target, -1) > rank[name]:
                            self.problem(path, line_of(text, match.start()),
                                         f"{name}/ includes from {target}/, listed after it in docs/layout.md")

    def run(self):
        self.check_layout()
        for path in self.markdown_files():
            with open(path, encoding="utf-8") as f:
                prose, blocks = split_markdown(f.read())
            self.check_links(path, prose)
            self.check_code(path, blocks)
        return self.problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary", help=f"the {PROGRAM} program whose --help the command lines are checked against")
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                        help="the repository's root (default: this script's parent folder's parent)")
    arguments = parser.parse_args()
    checker = Checker(arguments.root, arguments.binary)
    problems = checker.run()
    for problem in problems:
        print(problem)
    if not arguments.binary:
        print(f"check_docs: no --binary given, so {PROGRAM} command lines were not checked", file=sys.stderr)
    print(f"check_docs: {len(problems)} problems in {len(checker.markdown_files())} files "
          f"({checker.links} links, {checker.commands} command lines)", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
