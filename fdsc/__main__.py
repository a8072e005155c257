"""Command line of fdsc: ``python -m fdsc COMMAND ...``.

The library has no command of its own. Commands are found through the entry-point group
``fdsc.commands`` (an installed package registers ``name = "module:function"``, the function
taking the remaining arguments); the paper layer registers ``reproduce``. This keeps the
library free of any import of the paper layer.
"""

import sys
from importlib.metadata import EntryPoint, entry_points

__all__ = ["main", "commands"]


def commands() -> dict[str, EntryPoint]:
    """The registered commands: ``{name: entry point}`` of the group ``fdsc.commands``.

    Returns
    -------
    dict of str to importlib.metadata.EntryPoint
        Entry points by command name, sorted by name (empty if fdsc is not installed).
    """
    return {ep.name: ep for ep in sorted(entry_points(group="fdsc.commands"), key=lambda e: e.name)}


def main(argv: list[str] | None = None) -> int:
    """Run ``python -m fdsc COMMAND [ARGS]``.

    Without a command, or with ``-h``/``--help``, print the usage and the registered commands.

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status of the command; 0 for ``--help``, 2 for a missing or unknown command.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    found = commands()
    if not argv or argv[0] in ("-h", "--help") or argv[0] not in found:
        names = ", ".join(found) or "none (is fdsc installed with pip?)"
        msg = f"usage: python -m fdsc COMMAND [ARGS]; commands: {names}"
        if argv and argv[0] not in ("-h", "--help"):
            print(f"python -m fdsc: unknown command {argv[0]!r}; {msg}", file=sys.stderr)
            return 2
        print(msg)
        return 0 if argv else 2
    return found[argv[0]].load()(argv[1:])


if __name__ == "__main__":
    sys.exit(main())
