"""Tests of hexaleg.commands.parser: each command's help says what it does, how long it takes
and gives examples; a misspelt command or option gets a suggestion with the command's own
usage."""

from __future__ import annotations

import pytest

from hexaleg.cli import main


def test_each_command_s_help_says_what_it_does_how_long_and_examples(capsys):
    from hexaleg.commands.parser import GUIDE

    for command, (time, examples) in GUIDE.items():
        with pytest.raises(SystemExit):
            main([command, "--help"])
        out = " ".join(capsys.readouterr().out.split())
        assert f"takes {time}." in out and all(e in out for e in examples), command
        assert out.index("takes") > out.index("options:")  # after the options, as an epilog


@pytest.mark.parametrize(("argv", "says"), [
    (["desing"], "invalid choice: 'desing'.*(did you mean 'design'?)"),
    (["design", "--robt", "solo12"], "unrecognized arguments: --robt solo12 (did you mean "
                                     "'--robot'?)"),
])
def test_a_misspelt_command_or_option_gets_a_suggestion(argv, says, capsys):
    """#43: `hexaleg desing` and `--robt` said only what was wrong, not what was meant."""
    import re

    with pytest.raises(SystemExit) as e:
        main(argv)
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert re.search(re.escape(says).replace(r"\.\*", ".*"), err)
    # the usage printed is the command's own, not the top level's
    assert err.startswith(f"usage: hexaleg {argv[0]} " if len(argv) > 1 else "usage: hexaleg ")
