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


#: what reproduces a table's numbers: a kept script or example, a test file (or a test folder with the test's
#: name in the table) or node id, a subcommand of the ``roughcontact`` command
SCRIPT = re.compile(r"(?<![\w/])((?:studies|examples)/[\w.-]+\.(?:py|toml))")
TEST = re.compile(r"(?<![\w/])(tests/[\w/.-]*?(?:\.py(?:::\w+)?|/))(?![\w.])")
COMMAND = re.compile(r"(?<![\w/.-])(?<!import )(?<!from )roughcontact ([a-z][\w-]*)")
#: the header of a table of literature values or defaults whose rows each cite their source (a value or default
#: column and a source or basis column): its numbers are quoted, not computed here
SOURCED = re.compile(r"^(?=.*\|\s*(?:value|default)\s*\|)(?=.*\|\s*(?:[\w ]+ and )?(?:source|basis)\s*\|)")
TABLE_PAGES = sorted(page for page in (ROOT / "docs").rglob("*.md") if "dev" not in page.relative_to(ROOT).parts)


def sections(text):
    """The sections of a markdown page, each the list of its lines from one heading up to the next (headings in
    code blocks are code, not headings)."""
    parts, fenced = [[]], False
    for line in text.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        if not fenced and re.match(r"#{1,6} ", line):
            parts.append([])
        parts[-1].append(line)
    return parts


def numeric_tables(lines):
    """``(first line, body)`` of every markdown table among ``lines`` whose body holds a digit, except tables
    whose header has a source column (each row cites where its number comes from)."""
    tables, index = [], 0
    while index < len(lines) - 1:
        if lines[index].startswith("|") and re.fullmatch(r"\|[-:| ]+\|", lines[index + 1].strip()):
            end = index + 2
            while end < len(lines) and lines[end].startswith("|"):
                end += 1
            if re.search(r"\d", "\n".join(lines[index + 2:end])) and not SOURCED.search(lines[index]):
                tables.append((lines[index], "\n".join(lines[index + 2:end])))
            index = end
        else:
            index += 1
    return tables


def reproducers(lines):
    """What the section names that reproduces numbers: scripts, tests, ``roughcontact`` subcommands (in code) and
    Python blocks that tests/test_docs_examples.py runs."""
    text = "\n".join(lines)
    code = "\n".join(re.findall(r"^```\w*\n(.*?)^```", text, re.MULTILINE | re.DOTALL)
                     + re.findall(r"`([^`\n]+)`", re.sub(r"^```.*?^```", "", text, flags=re.MULTILINE | re.DOTALL)))
    named = ([("script", path) for path in SCRIPT.findall(text)] + [("test", path) for path in TEST.findall(text)]
             + [("command", name) for name in COMMAND.findall(code)])
    blocks = re.findall(r"^(?:(<!--[^\n]*-->)\n)?```python\n", text, re.MULTILINE)
    return named + [("block", "python")] * sum("not run by the tests" not in comment for comment in blocks)


def unreproduced_tables(text):
    """``(header, problem)`` per numeric table of a page whose section names no reproducing command, or names one
    that does not exist."""
    from roughcontact.cli import build_parser
    commands = set(next(action for action in build_parser()._actions if action.dest == "command").choices)
    problems = []
    for lines in sections(text):
        tables = numeric_tables(lines)
        if not tables:
            continue
        named = reproducers(lines)
        missing = []
        for kind, name in named:
            path, _, node = name.partition("::")
            if kind in ("script", "test") and not (ROOT / path).exists():
                missing.append(path)
            elif node and not re.search(rf"^\s*(def|class) {node}\b", (ROOT / path).read_text(), re.MULTILINE):
                missing.append(name)
            elif kind == "command" and name not in commands:
                missing.append(f"roughcontact {name}")
        for header, body in tables:
            if not named:
                problems.append((header, "no command, script or test in its section"))
            elif missing:
                problems.append((header, f"names what does not exist: {', '.join(missing)}"))
    return problems


def test_every_numeric_table_names_what_reproduces_it():
    """Outside docs/dev/, every table with a number in it shares its section (the lines between two headings)
    with the command, kept script or test that reproduces it, and what it names exists."""
    problems = [(page.relative_to(ROOT), header[:60], why) for page in TABLE_PAGES
                for header, why in unreproduced_tables(page.read_text())]
    assert not problems, "\n".join(map(str, problems))
    assert sum(len(numeric_tables(lines)) for page in TABLE_PAGES for lines in sections(page.read_text())) > 50


def test_a_table_without_its_command_is_found():
    """The check above fails on a table stripped of its command, on a script or test that does not exist and
    on an unknown subcommand; a heading inside a code block does not end a section."""
    table = "| grid | error |\n|---|---|\n| 128² | 16 % |\n"
    assert unreproduced_tables(f"# Page\n\n## Presets\n\n{table}")
    assert unreproduced_tables(f"## Presets\n\n`python studies/preset_pareto.py`\n\n### Front\n\n{table}")
    assert unreproduced_tables(f"## Presets\n\n`python studies/no_such_study.py`\n\n{table}")
    assert unreproduced_tables(f"## Presets\n\n`pytest tests/no_such_test.py`\n\n{table}")
    assert unreproduced_tables(f"## Presets\n\n`pytest tests/test_docs_pages.py::no_such_test`\n\n{table}")
    assert unreproduced_tables(f"## Presets\n\n`roughcontact no-such-command`\n\n{table}")
    assert not unreproduced_tables(f"## Presets\n\n`python studies/preset_pareto.py`\n\n{table}")
    assert not unreproduced_tables(f"## Presets\n\n```bash\n# a comment\nroughcontact run\n```\n\n{table}")
    assert not unreproduced_tables(f"## Presets\n\n`tests/test_docs_pages.py::sections`\n\n{table}")
    assert not unreproduced_tables("## Sources\n\n| quantity | value | source |\n|---|---|---|\n| ridge period | 0.5 mm | X |\n")
    assert unreproduced_tables("## Files\n\n| source | how it maps |\n|---|---|\n| columns | column 1 is x |\n")
