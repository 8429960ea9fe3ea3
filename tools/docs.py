#!/usr/bin/env python3
"""Regenerates every documented output of the README and the pictures it shows, or checks that they are
current (the ctest test `docs_outputs` runs the check, so the README never goes stale).

    tools/docs.py [--build DIR]            rewrite README.md's outputs and docs/*.png from a fresh run
    tools/docs.py --check [--build DIR]    exit 1 (with a diff) when a documented output or picture differs

What it regenerates (each documented with a marker the reader does not see, in README.md):
  - every fenced block whose first line starts with "$ ": a shell session. Its commands run in order, in one
    shell, in a scratch directory where build/ is the build directory and the repository's scenes/ and docs/
    are reachable; the lines after each command are replaced by its standard output.
  - <!-- docs: output of `CMD` --> before a fenced block: the block is CMD's standard output.
  - <!-- docs: watertight FILE... --> before a table: the table of `raykernel watertight FILE` for each file
    (10,000 lines, seed 1).
  - <!-- docs: spawn-audit FILE@E... --> before a table: the table of `raykernel spawn-audit FILE
    --scale-exponent E` for each (200 hits, seed 1).
  - Files under meshes/ are real meshes fetched by tools/fetch-audit-meshes.sh into build/audit-meshes (not
    in the repository; the network is needed once): a table or picture that names one is regenerated when
    they are there and left as it is (said on stderr) when they are not, so --check passes without them.
  - <!-- docs: pictures `CMD` --> : CMD writes pictures under docs/ (in the scratch directory, docs/ is a
    fresh directory that is then copied over the repository's, or compared with it byte for byte).

Numbers that depend on the machine (times, rates, thread counts) are compared as placeholders by --check and
written as measured otherwise.
"""
import argparse
import difflib
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCUMENTS = ["README.md"]

# Machine-dependent figures: replaced by a placeholder on both sides of a comparison.
VOLATILE = [
    (re.compile(r"\b\d[\d.,]*\s?(?:s|ms|µs)\b"), "<time>"),
    (re.compile(r"\b\d[\d.,]*\s?(?:k |M )?rays/s\b"), "<rate>"),
    (re.compile(r"\b\d+ threads?\b"), "<threads>"),
]


def normalized(text):
    for pattern, placeholder in VOLATILE:
        text = pattern.sub(placeholder, text)
    return text


class Scratch:
    """A scratch directory where the documented commands run: build/ is the build directory; scenes/, tests/
    examples/ and python/ are the repository's; docs/ is fresh (pictures are written there)."""

    def __init__(self, build):
        self.dir = tempfile.mkdtemp(prefix="raykernel-docs-")
        os.symlink(os.path.abspath(build), os.path.join(self.dir, "build"))
        for name in ("scenes", "tests", "examples", "python"):
            os.symlink(os.path.join(ROOT, name), os.path.join(self.dir, name))
        self.meshes = os.path.join(os.path.abspath(build), "audit-meshes")
        self.have_meshes = os.path.isdir(self.meshes)
        if self.have_meshes:
            os.symlink(self.meshes, os.path.join(self.dir, "meshes"))
        os.mkdir(os.path.join(self.dir, "docs"))
        self.env = dict(os.environ, PATH=os.path.join(os.path.abspath(build), "bin") + os.pathsep + os.environ["PATH"],
                        LC_ALL="C.UTF-8")

    def session(self, commands):
        """Runs the commands in order in one bash, returning each one's standard output."""
        marker = "@@raykernel-docs-%d@@"
        script = []
        for k, command in enumerate(commands):
            script.append("printf '%s\\n'" % (marker % k))
            script.append(command)
        out = subprocess.run(["bash", "-c", "\n".join(script)], cwd=self.dir, env=self.env, capture_output=True,
                             text=True)
        outputs = []
        parts = out.stdout.split("\n")
        current = None
        for line in parts:
            m = re.fullmatch(r"@@raykernel-docs-(\d+)@@", line)
            if m:
                current = []
                outputs.append(current)
            elif current is not None:
                current.append(line)
        while outputs and outputs[-1] and outputs[-1][-1] == "":
            outputs[-1].pop()
        if len(outputs) != len(commands):
            sys.exit("docs.py: a session did not run to its end:\n%s\n%s" % ("\n".join(commands), out.stderr))
        return outputs

    def output_of(self, command):
        return self.session([command])[0]

    def close(self):
        shutil.rmtree(self.dir)


def watertight_table(scratch, files):
    """The README's table of `raykernel watertight FILE` (10,000 lines, seed 1) for each file."""
    names = {"owned (raykernel)": "owned (raykernel)", "closed (raykernel)": "closed (raykernel)",
             "Moller-Trumbore": "Möller–Trumbore", "Embree": "Embree", "Embree robust": "Embree robust"}
    rows = ["| mesh (triangles) | method | leaks | double hits | misses | missed vertices |",
            "|---|---|---:|---:|---:|---:|"]
    for f in files:
        lines = scratch.output_of("build/bin/raykernel watertight %s --rays 10000 --seed 1" % f)
        m = re.match(r"mesh \S+: (\d+) triangles", lines[0])
        first = "%s (%s)" % (os.path.splitext(os.path.basename(f))[0], format(int(m.group(1)), ","))
        for line in lines[3:]:
            method = re.match(r"(owned \(raykernel\)|closed \(raykernel\)|Moller-Trumbore|Embree robust|Embree)\s", line)
            if not method:
                continue
            numbers = [format(int(n), ",") for n in re.findall(r"\d+", line[method.end():])]
            label = names[method.group(1)]
            if label == "owned (raykernel)":
                rows.append("| %s | %s | **%s** | (reference; unbalanced %s) | | |" % (first, label, numbers[0], numbers[1]))
            else:
                rows.append("| | %s | %s | %s | %s | %s |" % (label, *numbers))
            first = ""
    return rows


def spawn_audit_table(scratch, runs):
    """The README's table of `raykernel spawn-audit FILE --scale-exponent E` (200 hits, seed 1) for each FILE@E."""
    rows = ["| mesh (triangles), scale | method | format | new rays | no origin | self-hits | behind | on the plane | first hit differs | offset, ulps (median / max) |",
            "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for run in runs:
        f, e = run.rsplit("@", 1)
        lines = scratch.output_of("build/bin/raykernel spawn-audit %s --hits 200 --seed 1 --scale-exponent %s" % (f, e))
        m = re.match(r"mesh \S+: (\d+) triangles", lines[0])
        first = "%s (%s), 2^%s" % (os.path.splitext(os.path.basename(f))[0], format(int(m.group(1)), ","), e)
        for line in lines[3:]:
            cells = line.split()
            if len(cells) != 10:
                continue
            name, fmt, rays, no_origin, self_hits, behind, on_plane, differs, median, most = cells
            bold = (lambda x: "**%s**" % x) if name.startswith("raykernel") else (lambda x: x)
            rows.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s / %s |" % (
                first, bold(name), fmt, format(int(rays), ","), bold(format(int(no_origin), ",")),
                bold(format(int(self_hits), ",")),
                bold(format(int(behind), ",")), bold(format(int(on_plane), ",")), bold(format(int(differs), ",")),
                format(int(median), ","), format(int(most), ",")))
            first = ""
    return rows


def needs_missing_meshes(scratch, text):
    return "meshes/" in text and not scratch.have_meshes


FENCE = re.compile(r"^```")
MARKER = re.compile(r"^<!-- docs: (output of|watertight|spawn-audit|pictures) (.*?) -->$")


def regenerate(path, scratch):
    """The document with every marked output regenerated, and the pictures the markers asked for."""
    lines = open(path, encoding="utf-8").read().split("\n")
    out = []
    pictures = []
    i = 0
    while i < len(lines):
        line = lines[i]
        marker = MARKER.match(line)
        if marker:
            kind, argument = marker.group(1), marker.group(2)
            out.append(line)
            i += 1
            if kind == "output of":
                command = argument.strip("`")
                assert FENCE.match(lines[i]), "%s:%d: a fenced block must follow the marker" % (path, i + 1)
                out.append(lines[i])
                i += 1
                while not FENCE.match(lines[i]):
                    i += 1
                out.extend(scratch.output_of(command))
                out.append(lines[i])
                i += 1
            elif kind == "watertight":
                while i < len(lines) and lines[i].startswith("|"):
                    i += 1
                out.extend(watertight_table(scratch, argument.split()))
            elif kind == "spawn-audit":
                start = i
                while i < len(lines) and lines[i].startswith("|"):
                    i += 1
                if needs_missing_meshes(scratch, argument):
                    print("docs.py: kept the spawn-audit table of %s as it is (no build/audit-meshes: "
                          "tools/fetch-audit-meshes.sh fetches them)" % argument, file=sys.stderr)
                    out.extend(lines[start:i])
                else:
                    out.extend(spawn_audit_table(scratch, argument.split()))
            elif needs_missing_meshes(scratch, argument):
                print("docs.py: kept the pictures of %s (no build/audit-meshes)" % argument, file=sys.stderr)
            else:
                pictures.append(argument.strip("`"))
            continue
        if FENCE.match(line) and i + 1 < len(lines) and lines[i + 1].startswith("$ "):
            out.append(line)
            i += 1
            commands, body_end = [], i
            while not FENCE.match(lines[body_end]):
                if lines[body_end].startswith("$ "):
                    commands.append(lines[body_end][2:])
                body_end += 1
            outputs = scratch.session(commands)
            k = 0
            while i < body_end:
                if lines[i].startswith("$ "):
                    out.append(lines[i])
                    out.extend(outputs[k])
                    k += 1
                i += 1
            out.append(lines[i])
            i += 1
            continue
        out.append(line)
        i += 1
    for command in pictures:
        scratch.output_of(command)
    return "\n".join(out), pictures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="compare instead of rewriting")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="the build directory (default build/)")
    args = parser.parse_args()
    if not os.access(os.path.join(args.build, "bin", "raykernel"), os.X_OK):
        sys.exit("docs.py: no %s/bin/raykernel: build it first" % args.build)
    scratch = Scratch(args.build)
    stale = []
    try:
        for document in DOCUMENTS:
            path = os.path.join(ROOT, document)
            old = open(path, encoding="utf-8").read()
            new, pictures = regenerate(path, scratch)
            if args.check:
                if normalized(new) != normalized(old):
                    diff = difflib.unified_diff(normalized(old).split("\n"), normalized(new).split("\n"), document,
                                                document + " (fresh run)", lineterm="", n=1)
                    stale.append("\n".join(diff))
            elif new != old:
                open(path, "w", encoding="utf-8").write(new)
                print("docs.py: rewrote", document)
        for name in sorted(os.listdir(os.path.join(scratch.dir, "docs"))):
            fresh = os.path.join(scratch.dir, "docs", name)
            kept = os.path.join(ROOT, "docs", name)
            same = os.path.exists(kept) and open(fresh, "rb").read() == open(kept, "rb").read()
            if args.check and not same:
                stale.append("docs/%s differs from a fresh run of its command" % name)
            elif not args.check and not same:
                shutil.copyfile(fresh, kept)
                print("docs.py: rewrote docs/" + name)
    finally:
        scratch.close()
    if stale:
        print("\n\n".join(stale))
        print("\ndocs.py: the documented outputs above are stale; run tools/docs.py to regenerate them")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
