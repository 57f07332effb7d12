"""Every subcommand explains itself: a description, each option's help with its default, and
examples that parse."""
import argparse
import shlex

import pytest

from activegrain.cli import build_parser


def subcommands():
    parser = build_parser()
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return parser, action.choices


@pytest.mark.parametrize("name", sorted(subcommands()[1]))
def test_each_subcommand_has_description_defaults_and_examples(name):
    parser, commands = subcommands()
    sub = commands[name]
    assert sub.description and len(sub.description) > 60
    text = sub.format_help()
    assert "examples:\n  activegrain " + name in text
    for action in sub._actions:
        if isinstance(action, argparse._HelpAction):
            continue
        assert action.help, f"{name}: {action.dest} has no help"
        if action.option_strings and action.default not in (None, False):
            assert f"(default: {action.default})" in " ".join(text.split()), f"{name}: {action.dest}"
    examples = text.split("examples:\n")[1].splitlines()
    for line in examples:
        argv = shlex.split(line.strip())[1:]
        args = parser.parse_args(argv[:argv.index(">")] if ">" in argv else argv)   # no redirection
        assert args.command == name


def test_the_command_calls_itself_activegrain():
    parser, commands = subcommands()
    assert parser.prog == "activegrain" and parser.format_usage().startswith("usage: activegrain ")
    assert all(sub.prog == f"activegrain {name}" for name, sub in commands.items())


# reST markup that docstrings and help strings may carry, which a terminal would show as is
REST_MARKUP = ("``", ":func:", ":class:", ":meth:", ":mod:", ":data:", ":attr:", ":doc:", ":ref:", "`")


@pytest.mark.parametrize("name", [None] + sorted(subcommands()[1]))
def test_help_is_plain_text_without_rest_markup(name):
    parser, commands = subcommands()
    text = (parser if name is None else commands[name]).format_help()
    assert [m for m in REST_MARKUP if m in text] == [], text


def test_rest_markup_becomes_its_text():
    from activegrain.cli import _plain_text
    assert _plain_text("``--window`` (:func:`activegrain.analysis.classify_frames`, :class:`~a.b.Frame`, "
                       ":doc:`the page <continuum>`, `x`)") == (
        "--window (activegrain.analysis.classify_frames, Frame, the page, x)")


def test_dump_commands_take_the_time_step_in_seconds():
    parser, _ = subcommands()
    args = parser.parse_args(["snapshot", "a.dump", "-o", "a.png"])
    assert args.timestep is None and args.frame == -1
    assert parser.parse_args(["kymograph", "a.dump", "-o", "k.png"]).species == "beads"
