"""``python -m raykernel`` (and the ``raykernel`` console script, the same ``raykernel.__main__:main``): the C++
command-line tool compiled into the extension. The replay commands that raykernel.testing's failure reports print
must run with it and give the reference answer."""
import os
import re
import subprocess
import sys

import pytest

import raykernel as rk
from raykernel import _raykernel
from raykernel.testing import assert_matches_reference, assert_triangle_matches_reference

pytestmark = pytest.mark.skipif(not hasattr(_raykernel, "_cli_main"), reason="built without the command-line tool")


def run(args, stdin=""):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    return subprocess.run([sys.executable, "-m", "raykernel", *args], input=stdin, capture_output=True, text=True,
                          env=env, timeout=60)


def replay(report):
    """The replay line of a failure report, run with `python -m raykernel` in place of `raykernel`."""
    line = next(l for l in report.splitlines() if l.strip().startswith("replay"))
    command = line.split("replay", 1)[1].strip()
    text, tool = re.fullmatch(r"echo '(.*)' \| raykernel (.*)", command).groups()
    return run(tool.split(), text + "\n")


def test_version_help_and_unknown_commands():
    assert run(["--version"]).stdout == f"raykernel {rk.__version__}\n"
    assert "usage: raykernel <command>" in run(["--help"]).stdout
    bad = run(["nosuch"])
    assert bad.returncode == 2 and "unknown command 'nosuch'" in bad.stderr


def test_a_command_reads_standard_input_and_sets_the_exit_status():
    ok = run(["classify", "--exact-t"], "0 0 0 1 0 0 5 0 0 1 0 0\n")
    assert (ok.returncode, ok.stdout) == (0, "hit 5 5/1\n")
    bad = run(["classify"], "1 2 3\n")
    assert bad.returncode == 1 and bad.stdout.startswith("invalid")


def test_plane_failure_reports_replay():
    # A wrong t (0.2 for the exact 1/10): the report's replay line gives the reference answer.
    with pytest.raises(AssertionError) as failure:
        assert_matches_reference(((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0)), "hit", 0.2)
    out = replay(str(failure.value))
    assert out.returncode == 0, out.stderr
    relation, t = out.stdout.split()[:2]
    assert relation == "hit" and (float.fromhex(t) if t.startswith("0x") else float(t)) == 0.1, out.stdout


def test_triangle_failure_reports_replay():
    tri = ((0, 0, 0), (1, 0, 0), (0, 1, 0))
    ray = ((0.5, 0, -1), (0, 0, 3))
    wrong = rk.intersect(ray, tri)._replace(t=0.5)  # the exact t is 1/3
    with pytest.raises(AssertionError) as failure:
        assert_triangle_matches_reference(ray, tri, wrong)
    out = replay(str(failure.value))
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("hit") and "1/3" in out.stdout, out.stdout
