"""``python -m whipple ...``: the ``whipple`` command (see ``_cli.py``)."""

from ._cli import main

main()
