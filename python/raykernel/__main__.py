"""``python -m raykernel ARGS`` and the ``raykernel`` console script: the raykernel command-line tool (``raykernel
--help``), the same program as the C++ build's ``build/bin/raykernel``, compiled into the extension. The replay
commands ``raykernel.testing`` prints (``echo '...' | raykernel classify --exact-t --hex``) run with it."""

import sys


def main(argv=None) -> int:
    """Runs the tool on ``argv`` (default: ``sys.argv[1:]``) and returns its exit status."""
    from . import _raykernel

    run = getattr(_raykernel, "_cli_main", None)
    if run is None:
        print("raykernel: this build of the package has no command-line tool (it was built with "
              "RAYKERNEL_BUILD_CLI=OFF)", file=sys.stderr)
        return 2
    sys.stdout.flush()  # what Python printed before comes first
    sys.stderr.flush()
    return run(list(sys.argv[1:] if argv is None else argv))


if __name__ == "__main__":
    sys.exit(main())
