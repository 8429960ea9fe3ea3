"""The example suite (python/examples/) must be caught: raykernel's strategies find the NumPy ray–plane and
Möller–Trumbore code wrong, Hypothesis shrinks each counterexample, and the report says what is wrong; the
control (raykernel itself under the same check) passes. The README shows this output."""

import os
import pathlib
import re
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    import raykernel  # the package under test, wherever it is (build tree or installed): the child imports it too

    package_parent = str(pathlib.Path(raykernel.__file__).resolve().parent.parent)
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1",
               PYTHONPATH=os.pathsep.join([package_parent] + os.environ.get("PYTHONPATH", "").split(os.pathsep)))
    result = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q", "--tb=short", str(EXAMPLES)],
        cwd=tmp_path_factory.mktemp("examples"), env=env, capture_output=True, text=True, timeout=900,
    )
    return result


def test_the_numpy_code_fails_and_the_control_passes(run):
    out = run.stdout
    assert run.returncode == 1, out + run.stderr  # test failures, not an error
    assert re.search(r"^3 failed, 1 passed", out.splitlines()[-1]), out[-2000:]
    assert re.search(r"^FAILED \S*test_numpy_examples\.py::test_numpy_ray_plane_matches_raykernel", out, re.M)
    assert re.search(r"^FAILED \S*test_numpy_examples\.py::test_numpy_moller_trumbore_hits_edges_and_vertices", out, re.M)
    assert re.search(r"^FAILED \S*test_numpy_examples\.py::test_numpy_moller_trumbore_without_epsilon_hits_edges_and_vertices",
                     out, re.M)
    assert "test_control_raykernel_passes_the_same_check" not in out.split("short test summary")[-1]


def test_each_failure_shows_a_shrunk_counterexample_and_the_report(run):
    out = run.stdout
    assert "Falsifying example: test_numpy_ray_plane_matches_raykernel(" in out
    assert "Falsifying example: test_numpy_moller_trumbore_hits_edges_and_vertices(" in out
    assert "Falsifying example: test_numpy_moller_trumbore_without_epsilon_hits_edges_and_vertices(" in out
    assert out.count("raykernel reference check FAILED") >= 3
    # Without an epsilon, what Möller–Trumbore misses is a ray exactly through an edge or a vertex.
    section = out.index("_ test_numpy_moller_trumbore_without_epsilon_hits_edges_and_vertices _")
    no_epsilon = out[section:out.index("Falsifying example: test_numpy_moller_trumbore_without_epsilon", section)]
    assert re.search(r"expected  hit   \((edge-(ab|bc|ca)|vertex-[abc]), hit under the closed rule\)", no_epsilon)
    assert "| raykernel classify --exact-t --hex" in out and "| raykernel triangle --rule=closed --exact" in out
    # Shrunk: a single query each, not the list Hypothesis first failed on.
    for name in ("QueryArrays", "TriangleQueryArrays"):
        printed = re.search(name + r"\(origins=np\.array\((\[\[.*?\]\])\)", out, re.S)
        assert printed and printed.group(1).count("[") == 2, printed and printed.group(1)


@pytest.mark.skipif(not os.environ.get("RAYKERNEL_CLI"), reason="the CLI is not built (RAYKERNEL_CLI)")
def test_the_reports_replay_line_gives_the_expected_answer(run):
    # The ray–plane report's replay command, through the real CLI: its answer is the report's "expected".
    replay = re.search(r"replay    echo '([^']*)' \| raykernel classify --exact-t --hex", run.stdout).group(1)
    expected = re.search(r"expected  ([a-z-]+) +t = (\S+)", run.stdout)
    cli = subprocess.run([os.environ["RAYKERNEL_CLI"], "classify", "--exact-t", "--hex"], input=replay + "\n",
                         capture_output=True, text=True, check=True).stdout.split()
    assert cli[0] == expected.group(1) and float.fromhex(cli[1]) == float.fromhex(expected.group(2))
