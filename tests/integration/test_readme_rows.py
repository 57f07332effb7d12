"""The README's table of results says what docs/validation.md's summary says: each README row's
status is the status of a summary row for the same evidence (the validation.md section it links),
every time it quotes (a number of seconds) is in those summary rows, and the README's caption
describes a run that validation.md describes. A row edited on one side only fails here."""
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text()
VALIDATION = (ROOT / "docs" / "validation.md").read_text()
STATUSES = ("reproduced", "partial", "differs", "not tested", "mixed physics")
SECONDS = re.compile(r"(\d+(?:\.\d+)?)(?:-\d+)? s\b")


def table_rows(text, heading):
    """The body rows (lists of cells) of the first table after the line ``heading``."""
    lines = text[text.index(heading):].splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("|"))
    rows = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        rows.append([cell.strip() for cell in line.strip().strip("|").split(" | ")])
    return rows


def summary_by_section():
    """validation.md's summary: per section anchor, the (ours, status) of its rows."""
    by_anchor = {}
    for claim, _paper, ours, status, _figure in table_rows(VALIDATION, "## Summary"):
        anchor = re.search(r"\]\(#([^)]+)\)", claim).group(1)
        by_anchor.setdefault(anchor, []).append((ours, status))
    return by_anchor


README_ROWS = table_rows(README, "## What it reproduces")


def test_every_status_follows_the_rules():
    for rows in summary_by_section().values():
        for _ours, status in rows:
            assert status.startswith(STATUSES), status


@pytest.mark.parametrize("row", README_ROWS, ids=[r[0][:40] for r in README_ROWS])
def test_readme_row_matches_the_summary(row):
    _claim, ours, status = row
    summary = summary_by_section()
    anchors = re.findall(r"docs/validation\.md#([^)]+)\)", ours)
    assert anchors, f"README row links no validation.md section: {ours}"
    statuses = [s.strip() for s in status.split(";")]
    assert len(statuses) in (1, len(anchors)), status
    for k, anchor in enumerate(anchors):
        assert anchor in summary, f"no summary row for #{anchor}"
        expected = {s for _, s in summary[anchor]}
        assert statuses[min(k, len(statuses) - 1)] in expected, (anchor, status, expected)
    quoted = set(SECONDS.findall(ours))
    told = {t for a in anchors for o, _ in summary[a] for t in re.findall(r"\d+(?:\.\d+)?", o)}
    assert quoted <= told, f"README quotes {sorted(quoted - told)} s, which the summary does not"


def test_readme_caption_describes_a_validation_run():
    caption = README[README.index("*The condensed channel"):README.index("## Two commands")]
    time = re.search(r"at (\d+) s\. A\s+row\s+of (\d+) rods", caption)
    assert time, "the caption no longer says at what time and with how many rods"
    section = " ".join(VALIDATION[VALIDATION.index("## The condensed channel"):
                                  VALIDATION.index("## The full-size channel")].split())
    assert f"{time.group(1)} s" in section and f"row of {time.group(2)} rods" in section
    assert "channel-small-condensed-500s" in section
