#!/usr/bin/env python3
"""Checks that the ClusterFuzzLite configuration is what the build and the docs need (run by ci-check.sh,
which cannot run Docker or GitHub Actions here):

- project.yaml: language c++, sanitizers address and undefined (the ones the workflows use);
- Dockerfile: FROM base-builder, the source copied to $SRC/raykernel, WORKDIR there, build.sh copied to $SRC,
  and the Ubuntu packages that hold every static archive build.sh asks for (static_lib libX.a) and the
  headers CMake needs;
- the workflows: the documented build_fuzzers/run_fuzzers steps, language c++, both sanitizers, code-change
  mode on pull requests and batch mode on a schedule;
- the users' template (examples/clusterfuzzlite/): the same for its Dockerfile, project.yaml and build.sh.
Needs PyYAML (Debian python3-yaml, installed with the Python packages); run with /usr/bin/python3.
"""

import pathlib
import re
import sys

import yaml

ROOT = pathlib.Path(__file__).resolve().parent.parent
# The Ubuntu package of each static archive build.sh links, and the packages CMake's find_package needs.
ARCHIVE_PACKAGES = {"libgmp.a": "libgmp-dev", "libgmpxx.a": "libgmp-dev", "libmpfr.a": "libmpfr-dev",
                    "libpng16.a": "libpng-dev", "libz.a": "zlib1g-dev"}
errors = []


def check(condition, message):
    if not condition:
        errors.append(message)


def dockerfile(path: pathlib.Path, project_dir: str, build_sh: pathlib.Path, extra_packages) -> None:
    text = path.read_text()
    lines = [l.strip() for l in re.sub(r"\\\n", " ", text).splitlines() if l.strip() and not l.startswith("#")]
    check(lines and re.match(r"FROM gcr\.io/oss-fuzz-base/base-builder(:\S+)?$", lines[0]), f"{path}: FROM base-builder")
    check(f"COPY . $SRC/{project_dir}" in lines, f"{path}: COPY . $SRC/{project_dir}")
    check(f"WORKDIR $SRC/{project_dir}" in lines, f"{path}: WORKDIR $SRC/{project_dir}")
    check("COPY .clusterfuzzlite/build.sh $SRC/" in lines, f"{path}: COPY .clusterfuzzlite/build.sh $SRC/")
    installed = set(re.findall(r"[a-z0-9][a-z0-9+.-]*-dev|\bzip\b|ninja-build", " ".join(l for l in lines if "apt-get install" in l)))
    for archive in re.findall(r"static_lib (lib\S+\.a)", build_sh.read_text()):
        package = ARCHIVE_PACKAGES.get(archive)
        check(package is not None, f"{build_sh}: {archive} has no package in check_config.py's ARCHIVE_PACKAGES")
        check(package in installed, f"{path}: build.sh links {archive}; the Dockerfile must install {package}")
    for package in extra_packages:
        check(package in installed, f"{path}: install {package}")


def project_yaml(path: pathlib.Path) -> None:
    data = yaml.safe_load(path.read_text())
    check(data.get("language") == "c++", f"{path}: language: c++")
    check(set(data.get("sanitizers", [])) == {"address", "undefined"}, f"{path}: sanitizers address and undefined")


def workflow(path: pathlib.Path, mode: str, trigger: str) -> None:
    data = yaml.safe_load(path.read_text())
    on = data.get("on", data.get(True))  # YAML 1.1 reads the key `on` as true
    check(isinstance(on, dict) and trigger in on, f"{path}: triggered by {trigger}")
    for name, job in data["jobs"].items():
        check(set(job["strategy"]["matrix"]["sanitizer"]) == {"address", "undefined"}, f"{path}: {name} sanitizers")
        steps = {s["uses"].split("@")[0]: s for s in job["steps"] if "uses" in s}
        build = steps.get("google/clusterfuzzlite/actions/build_fuzzers")
        run = steps.get("google/clusterfuzzlite/actions/run_fuzzers")
        check(build is not None and build["with"]["language"] == "c++", f"{path}: build_fuzzers with language c++")
        check(run is not None and run["with"]["mode"] == mode, f"{path}: run_fuzzers in {mode} mode")
        check(run is not None and int(run["with"]["fuzz-seconds"]) > 0, f"{path}: fuzz-seconds")
        for step in (build, run):
            check(step is not None and step["with"]["sanitizer"] == "${{ matrix.sanitizer }}", f"{path}: sanitizer from the matrix")


cf = ROOT / ".clusterfuzzlite"
dockerfile(cf / "Dockerfile", "raykernel", cf / "build.sh", ["libcgal-dev", "nlohmann-json3-dev", "zip", "ninja-build"])
project_yaml(cf / "project.yaml")
workflow(ROOT / ".github/workflows/cflite_pr.yml", "code-change", "pull_request")
workflow(ROOT / ".github/workflows/cflite_batch.yml", "batch", "schedule")
template = ROOT / "examples/clusterfuzzlite"
dockerfile(template / "Dockerfile", "myproject", template / "build.sh", ["libcgal-dev", "zip"])
project_yaml(template / "project.yaml")

if errors:
    print("check_config: FAILED\n  " + "\n  ".join(errors), file=sys.stderr)
    sys.exit(1)
print("check_config: Dockerfile, project.yaml, workflows and the users' template are consistent")
