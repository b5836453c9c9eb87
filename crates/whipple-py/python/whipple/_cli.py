"""The ``whipple`` command installed with the package (``[project.scripts]`` in pyproject.toml):
the same CLI as the Rust binary, run by the native module in this process.

``python -m whipple eig --bike benchmark`` does the same (``__main__.py``).
"""

import sys

from . import _whipple


def main() -> None:
    """Runs ``whipple`` with ``sys.argv`` and exits with its status."""
    argv = ["whipple", *sys.argv[1:]]
    sys.stdout.flush()
    sys.stderr.flush()
    sys.exit(_whipple.cli_main(argv))


if __name__ == "__main__":
    main()
