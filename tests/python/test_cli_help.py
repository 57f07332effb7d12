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
    assert "examples:\n  python3 -m activegrain " + name in text
    for action in sub._actions:
        if isinstance(action, argparse._HelpAction):
            continue
        assert action.help, f"{name}: {action.dest} has no help"
        if action.option_strings and action.default not in (None, False):
            assert f"(default: {action.default})" in " ".join(text.split()), f"{name}: {action.dest}"
    examples = text.split("examples:\n")[1].splitlines()
    for line in examples:
        argv = shlex.split(line.strip())[3:]
        args = parser.parse_args(argv[:argv.index(">")] if ">" in argv else argv)   # no redirection
        assert args.command == name


def test_dump_commands_take_the_time_step_in_seconds():
    parser, _ = subcommands()
    args = parser.parse_args(["snapshot", "a.dump", "-o", "a.png"])
    assert args.timestep is None and args.frame == -1
    assert parser.parse_args(["kymograph", "a.dump", "-o", "k.png"]).species == "beads"
