"""The docs as reference (issue 54): every relative link of README.md and docs/*.md resolves
inside the repository (a file, and for ``#anchor`` into Markdown a heading by GitHub's anchor
rules), no path reference leaves the repository, quoted pointers to a doc's section
(``docs/DESIGN_NOTES.md, "Section"``) name an existing heading (or bold label), and docs/DESIGN_NOTES.md stays
short, each of its sections naming a file or symbol that exists in the sources.

Pure Python on the repository's text: needs no build and does not import geofair.
"""

from __future__ import annotations

import re
import unicodedata
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
DESIGN_NOTES = ROOT / "docs" / "DESIGN_NOTES.md"
MAX_DESIGN_NOTES_LINES = 400
# Where the symbols and files that DESIGN_NOTES' headings name live.
SOURCE_DIRS = ("native", "addon", "dev", "bench", "scripts", "examples")
SOURCE_SUFFIXES = {".h", ".hpp", ".cpp", ".c", ".py", ".pyi", ".sh", ".cmake", ".toml", ".txt"}
# Where quoted pointers to a doc's section are looked for (comments, docstrings, docs).
POINTER_DIRS = (*SOURCE_DIRS, "tests", "docs")

FENCE = re.compile(r"^(```|~~~).*?^\1[^\n]*$", re.MULTILINE | re.DOTALL)
CODE_SPAN = re.compile(r"`[^`\n]*`")
# [text](target "title") and ![alt](target); the text may span lines and hold [brackets].
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEFINITION = re.compile(r"^ {0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)", re.MULTILINE)
HTML_LINK = re.compile(r"""\b(?:href|src)\s*=\s*["']([^"']+)["']""")
# A path that climbs with ../ (not the ".../" of an elided path).
PARENT_PATH = re.compile(r"(?<![\w./])((?:\.\./)+[^\s`'\"()<>\[\]]*)")
ATX_HEADING = re.compile(r"^ {0,3}(#{1,6})[ \t]+(.*?)(?:[ \t]+#+)?[ \t]*$")
HTML_ANCHOR = re.compile(r"""<a\s+(?:name|id)\s*=\s*["']([^"']+)["']""")
# A quoted pointer to a section: DOC.md, "Section" (and "Other section").
SECTION_POINTER = re.compile(r"\b([A-Z][A-Z_]*\.md)\)?,\s*((?:\"[^\"]{1,200}\"(?:\s*,\s*|\s+and\s+)?)+)")
COMMENT_CONTINUATION = re.compile(r"[ \t]*\n[ \t]*(?:///?|#|\*)?[ \t]*")
# A paragraph's bold label, "**Negative cotangent weights.** ...", which pointers name too.
BOLD_LABEL = re.compile(r"^(?:[-*] )?\*\*([^*\n]+?)\.?\*\*", re.MULTILINE)


def rel(path: Path) -> str:
    return path.relative_to(ROOT).as_posix()


def without_code(text: str) -> str:
    """The text without fenced code blocks (their lines kept empty, so line numbers hold)."""
    return FENCE.sub(lambda m: "\n" * m.group(0).count("\n"), text)


def line_of(text: str, index: int) -> int:
    return text.count("\n", 0, index) + 1


def github_anchor(heading: str) -> str:
    """GitHub's anchor of a heading: its rendered text lower-cased, punctuation dropped
    (letters, digits, '-' and '_' kept), each space a hyphen."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text
    text = re.sub(r"<[^>]+>", "", text).replace("`", "")
    kept = []
    for ch in text.lower():
        if ch == " ":
            kept.append("-")
        elif ch in "-_" or unicodedata.category(ch)[0] in "LN":
            kept.append(ch)
    return "".join(kept)


@cache
def headings(path: Path) -> tuple[str, ...]:
    """The headings of a Markdown file, in order, as written (outside fenced code)."""
    lines = without_code(path.read_text(encoding="utf-8")).split("\n")
    found = []
    for i, line in enumerate(lines):
        m = ATX_HEADING.match(line)
        if m:
            found.append(m.group(2).strip())
        elif i > 0 and lines[i - 1].strip() and re.fullmatch(r" {0,3}(=+|-+)[ \t]*", line):
            previous = lines[i - 1].strip()
            if not previous.startswith(("|", "-", "*", "#", ">")):
                found.append(previous)
    return tuple(found)


@cache
def anchors(path: Path) -> frozenset[str]:
    """The anchors GitHub gives a Markdown file's headings (repeats get -1, -2, ...), and
    explicit <a name/id> anchors."""
    seen: dict[str, int] = {}
    result = set()
    for heading in headings(path):
        anchor = github_anchor(heading)
        count = seen.get(anchor, 0)
        seen[anchor] = count + 1
        result.add(anchor if count == 0 else f"{anchor}-{count}")
    result.update(HTML_ANCHOR.findall(path.read_text(encoding="utf-8")))
    return frozenset(result)


def links(text: str) -> list[tuple[int, str]]:
    """(line, target) of every link and image of a Markdown text, outside code."""
    text = without_code(text)
    text = CODE_SPAN.sub(lambda m: " " * len(m.group(0)), text)
    found = []
    for pattern in (INLINE_LINK, REFERENCE_DEFINITION, HTML_LINK):
        found += [(line_of(text, m.start(1)), m.group(1)) for m in pattern.finditer(text)]
    return sorted(found)


def is_external(target: str) -> bool:
    return bool(re.match(r"[A-Za-z][A-Za-z0-9+.-]*:", target))


def inside(path: Path) -> bool:
    return path.resolve().is_relative_to(ROOT)


@pytest.mark.parametrize("doc", DOCS, ids=rel)
def test_links_resolve_inside_the_repository(doc: Path) -> None:
    text = doc.read_text(encoding="utf-8")
    problems = []
    for line, target in links(text):
        if not target or is_external(target):
            continue
        where = f"{rel(doc)}:{line}: link {target!r}"
        path_part, _, anchor = target.partition("#")
        if path_part.startswith("/"):
            problems.append(f"{where}: an absolute path")
            continue
        path = (doc.parent / path_part).resolve() if path_part else doc
        if not inside(path):
            problems.append(f"{where}: leaves the repository")
        elif not path.exists():
            problems.append(f"{where}: no such file {rel(path)}")
        elif anchor and path.suffix == ".md" and anchor not in anchors(path):
            problems.append(f"{where}: no heading with anchor #{anchor} in {rel(path)}")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("doc", DOCS, ids=rel)
def test_no_path_reference_leaves_the_repository(doc: Path) -> None:
    """A path that climbs with ../ (in a link, in code or in prose) stays inside the
    repository and names something that exists there."""
    text = doc.read_text(encoding="utf-8")
    problems = []
    for m in PARENT_PATH.finditer(text):
        reference = m.group(1).rstrip(".,;:")
        path = (doc.parent / reference.partition("#")[0]).resolve()
        where = f"{rel(doc)}:{line_of(text, m.start(1))}: {reference!r}"
        if not inside(path):
            problems.append(f"{where} leaves the repository")
        elif not path.exists():
            problems.append(f"{where}: no such file {rel(path)}")
    assert not problems, "\n".join(problems)


def test_design_notes_are_short() -> None:
    count = len(DESIGN_NOTES.read_text(encoding="utf-8").splitlines())
    assert count < MAX_DESIGN_NOTES_LINES, (
        f"{rel(DESIGN_NOTES)} has {count} lines (at most {MAX_DESIGN_NOTES_LINES - 1}): keep the reasons "
        "there, short, and move trials and per-case figures to docs/LOG.md"
    )


@cache
def source_files() -> tuple[Path, ...]:
    return tuple(
        path
        for directory in SOURCE_DIRS
        for path in sorted((ROOT / directory).rglob("*"))
        if path.is_file() and path.suffix in SOURCE_SUFFIXES
    )


@cache
def source_words() -> frozenset[str]:
    words: set[str] = set()
    for path in source_files():
        words.update(re.findall(r"\w+", path.read_text(encoding="utf-8", errors="replace")))
    return frozenset(words)


def exists_in_sources(name: str) -> bool:
    """A file name (or repository path) or an identifier (Class::member too) of the sources."""
    if re.search(r"\.(h|hpp|cpp|c|py|sh|toml|md)$", name):
        if "/" in name:
            return (ROOT / name).exists()
        return any(path.name == name for path in source_files())
    return all(part in source_words() for part in name.split("::"))


def named_in_heading(heading: str) -> list[str]:
    """The files and symbols a DESIGN_NOTES heading names: the items of its closing
    parenthesis (split at ',', ';' and ': ') that are single words, and the code-like words of
    its title (with '_' or '::', kConstant, CamelCase)."""
    names = []
    title, parenthesis = heading, ""
    m = re.search(r"\(([^()]*)\)\s*$", heading)
    if m:
        title, parenthesis = heading[: m.start()], m.group(1)
    for item in re.split(r"[,;]|:\s", parenthesis):
        item = item.strip().strip("`")
        if item and not re.search(r"\s", item) and re.fullmatch(r"[\w.:/]+", item):
            names.append(item)
    for word in re.findall(r"[\w:]+", title.replace("'s", "")):
        word = word.strip(":")
        if "_" in word or "::" in word or re.fullmatch(r"k[A-Z]\w*|[A-Z][a-z]+[A-Z]\w*", word):
            names.append(word)
    return names


def design_notes_sections() -> list[str]:
    return [h for h in headings(DESIGN_NOTES) if not h.startswith("Design notes")]


@pytest.mark.parametrize("heading", design_notes_sections())
def test_design_notes_sections_name_what_exists(heading: str) -> None:
    names = named_in_heading(heading)
    assert names, f"{rel(DESIGN_NOTES)}, section {heading!r}: names no file or symbol (as '(file.h, Symbol)')"
    missing = [name for name in names if not exists_in_sources(name)]
    assert not missing, (
        f"{rel(DESIGN_NOTES)}, section {heading!r}: {missing} not found in {', '.join(SOURCE_DIRS)} "
        "(renamed or removed? fix the heading)"
    )


def pointer_files() -> list[Path]:
    files = [ROOT / "README.md"]
    for directory in POINTER_DIRS:
        files += [
            path
            for path in sorted((ROOT / directory).rglob("*"))
            if path.is_file() and path.suffix in SOURCE_SUFFIXES | {".md"}
        ]
    return files


def test_section_pointers_name_existing_sections() -> None:
    """A pointer to a doc's section in a comment, docstring or doc (the doc's name, a comma,
    the section's title in double quotes; the quote may wrap onto a comment's next line) names
    the start of a heading or of a paragraph's bold label in that doc."""
    problems = []
    for path in pointer_files():
        if path == Path(__file__).resolve():
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        joined = COMMENT_CONTINUATION.sub(" ", text)
        for m in SECTION_POINTER.finditer(joined):
            name = m.group(1)
            doc = next((d for d in (ROOT / "docs" / name, ROOT / name) if d.exists()), None)
            quoted = re.findall(r"\"([^\"]+)\"", m.group(2))
            if doc is None:
                problems.append(f"{rel(path)}: {name}, {quoted}: no such doc")
                continue
            labels = BOLD_LABEL.findall(without_code(doc.read_text(encoding="utf-8")))
            titles = [t.replace("`", "") for t in (*headings(doc), *labels)]
            for section in quoted:
                if not any(t.startswith(section.replace("`", "")) for t in titles):
                    problems.append(f"{rel(path)}: {name}, {section!r}: no such section in {rel(doc)}")
    assert not problems, "\n".join(problems)
