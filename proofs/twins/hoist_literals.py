#!/usr/bin/env python3
"""Hoists the integer literals of the extracted twins (twins.ml) out of the functions that use them.

ExtrOcamlZBigInt extracts a positive literal as its constructors, e.g. 53 as
  ((fun x -> Big_int_Z.succ_big_int (Big_int_Z.mult_int_big_int 2 x)) (Big_int_Z.mult_int_big_int 2 (... Big_int_Z.unit_big_int)))
which OCaml (without flambda) evaluates again at every call: Flocq's operations pass prec = 53 and emax = 1024 so,
and building them was a third of the runner's time. This rewrites every such closed expression into the name of
a top-level constant of the same value, defined once at the head of the file. The expressions are pure and
closed, so the extracted functions compute what they computed; the differential runner checks the result.

Usage: hoist_literals.py TWINS_ML
"""
import re
import sys

XI = r"\(fun\s+x\s+->\s+Big_int_Z\.succ_big_int\s+\(Big_int_Z\.mult_int_big_int\s+2\s+x\)\)"
XO = r"Big_int_Z\.mult_int_big_int\s+2"
LIT = r"twin_literal_(\d+)"


def hoist(text):
    values = {}

    def name(v):
        values[v] = True
        return "twin_literal_%d" % v

    text = re.sub(r"Big_int_Z\.unit_big_int", lambda m: name(1), text)
    rules = [
        (re.compile(r"\(\s*" + LIT + r"\s*\)"), lambda n: n),
        (re.compile(r"\(\s*" + XI + r"\s+" + LIT + r"\s*\)"), lambda n: 2 * n + 1),
        (re.compile(r"\(\s*" + XO + r"\s+" + LIT + r"\s*\)"), lambda n: 2 * n),
        (re.compile(XI + r"\s+" + LIT + r"\b"), lambda n: 2 * n + 1),
        (re.compile(XO + r"\s+" + LIT + r"\b"), lambda n: 2 * n),
    ]
    changed = True
    while changed:
        changed = False
        for pattern, value in rules:
            text, count = pattern.subn(lambda m: name(value(int(m.group(1)))), text)
            changed = changed or count > 0
    used = sorted(v for v in values if re.search(r"\btwin_literal_%d\b" % v, text))
    head = "".join("let twin_literal_%d = Big_int_Z.big_int_of_string \"%d\"\n" % (v, v) for v in used)
    return head + "\n" + text, len(used)


def main():
    path = sys.argv[1]
    with open(path) as f:
        text = f.read()
    text, count = hoist(text)
    with open(path, "w") as f:
        f.write(text)
    print("hoist_literals: %d literals hoisted in %s" % (count, path))


if __name__ == "__main__":
    main()
