"""Exit codes of the workflow scripts: 2 for bad input, 1 for a run that failed, each with one
line on stderr that names the script. Standard library only."""
import os
import sys


class InputError(Exception):
    """Bad input (a missing file, a bad option): exit code 2."""


class RunError(Exception):
    """A run failed or gave a wrong result: exit code 1."""


def run_main(main, input_errors=()):
    """sys.exit(main(argv)), with InputError (and the exception types in input_errors) as exit
    code 2 and RunError as exit code 1."""
    program = os.path.basename(sys.argv[0])
    try:
        sys.exit(main(sys.argv[1:]))
    except (InputError, *input_errors) as error:
        print(f"{program}: {error}", file=sys.stderr)
        sys.exit(2)
    except RunError as error:
        print(f"{program}: {error}", file=sys.stderr)
        sys.exit(1)
