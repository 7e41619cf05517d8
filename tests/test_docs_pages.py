"""The documentation keeps its promises: every relative link resolves (to a file, and to a heading or an
anchor of a page), every test that docs/validation/index.md names exists, and no page names a commit or points
into the git history (the history is CHANGELOG.md's)."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
VALIDATION = ROOT / "docs" / "validation" / "index.md"
PAGES = sorted([*(ROOT / "docs").rglob("*.md"), ROOT / "README.md", ROOT / "CHANGELOG.md",
                ROOT / "examples" / "README.md"])
#: a relative link to a file (its target has a dot or a slash) and its anchor
LINK = re.compile(r"\]\(((?![a-z]+:)[^)\s#]*[./][^)\s#]*)(#[^)\s]+)?\)")
#: a commit hash: 7-40 hex digits with at least one letter and one digit, not part of a number (8.85e-12)
HASH = re.compile(r"(?<![.\w])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}(?![\w-])")


def named_tests():
    """``(file, name or None)`` for every test a validation table names; a table's header gives the folder."""
    folder, file, named = ROOT / "tests", None, []
    for line in VALIDATION.read_text().splitlines():
        header = re.match(r"\| check \|.*\| test \(`([^`]+)`\) \|$", line)
        if header:
            folder = ROOT / header.group(1)
            continue
        if not line.startswith("| ") or line.startswith("|---"):
            continue
        for token in re.findall(r"`([^`]*\.py(?:::\w+)?|::\w+)`", line.rsplit("|", 2)[-2]):
            path, _, name = token.partition("::")
            if path:
                file = ROOT / path if path.startswith("tests/") else folder / path
            named.append((file, name or None))
    return named


def test_validation_tables_name_existing_tests():
    named = named_tests()
    assert len(named) > 50
    for file, name in named:
        assert file is not None and file.is_file(), file
        if name:
            assert re.search(rf"^\s*(def|class) {name}\b", file.read_text(), re.MULTILINE), f"{file.name}::{name}"


def test_no_page_names_a_commit_or_the_git_history():
    for page in (ROOT / "docs").rglob("*.md"):
        text = page.read_text()
        assert not HASH.findall(text), (page, HASH.findall(text))
        assert "git history" not in text, page


def anchors(page):
    """GitHub's anchors of a page: its headings (lower case, punctuation dropped, spaces to hyphens) and the
    ids of its explicit anchors."""
    text = page.read_text()
    headings = re.findall(r"^#+ (.*)$", text, re.MULTILINE)
    return ({re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-") for heading in headings}
            | set(re.findall(r'<a (?:id|name)="([^"]+)"', text)))


def test_relative_links_resolve():
    checked = 0
    for page in PAGES:
        for target, anchor in LINK.findall(page.read_text()):
            path = (page.parent / target).resolve()
            assert path.exists(), f"{page.relative_to(ROOT)}: {target}"
            if anchor and path.suffix == ".md":
                assert anchor[1:] in anchors(path), f"{page.relative_to(ROOT)}: {target}{anchor}"
            checked += 1
    assert checked > 100


def test_every_page_is_reachable_from_the_index():
    """docs/index.md links everything: every page under docs/ is reached from it by relative links."""
    reached, todo = set(), [ROOT / "docs" / "index.md"]
    while todo:
        page = todo.pop()
        if page in reached or page.suffix != ".md" or not page.is_relative_to(ROOT / "docs"):
            continue
        reached.add(page)
        todo += [(page.parent / target).resolve() for target, _ in LINK.findall(page.read_text())]
    assert set((ROOT / "docs").rglob("*.md")) - reached == set()
