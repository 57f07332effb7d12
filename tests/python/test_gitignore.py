"""Running the README's commands for the minimal deck in the checkout leaves no untracked file:
what the deck and the snapshot command write is in .gitignore."""
import pathlib
import re
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
MINIMAL = ROOT / "examples" / "minimal"


def written_by_the_minimal_deck_and_readme():
    """The files the README's lines for examples/minimal write there: the deck's log, its dumps
    (``dump ID group style N FILE``) and the snapshot command's ``-o`` image."""
    names = {"log.lammps"}
    for line in (MINIMAL / "in.minimal").read_text().splitlines():
        words = line.split("#")[0].split()
        if words[:1] == ["dump"]:
            names.add(words[5])
    readme = (ROOT / "README.md").read_text()
    block = readme[readme.index("cd examples/minimal && lmp -in in.minimal"):].split("```")[0]
    names.update(re.findall(r"-o (\S+)", block))
    return sorted(names)


def test_the_minimal_decks_outputs_are_ignored_by_git():
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")
    names = written_by_the_minimal_deck_and_readme()
    assert {"minimal.dump", "snapshot.png"} <= set(names)
    paths = [str((MINIMAL / n).relative_to(ROOT)) for n in names]
    done = subprocess.run(["git", "check-ignore", "--no-index", *paths], cwd=ROOT, capture_output=True, text=True)
    assert sorted(done.stdout.split()) == sorted(paths), done.stderr
