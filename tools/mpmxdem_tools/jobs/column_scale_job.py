#!/usr/bin/python3
"""A column-collapse job at another size: the same material and aspect ratio, lengths scaled.

A continuum has no grain size, but the RVEs have one: their inertial number I = gamma_dot d50 /
sqrt(p / rho_s) sets the rate dependence of their friction, and in a column of length L0 under
gravity I scales as d50 / L0 (gamma_dot ~ sqrt(g / L0), p ~ rho g L0). So an MPM x DEM column can
be compared with a pure-DEM column of the same grains only at the same L0 / d50. This tool writes
the job of a column at another size L0', keeping the grains, the density, gravity and the aspect
ratio (docs/validation/column_collapse.md, "At the grains' own size"). With s = L0' / L0:

- lengths x s: [mpm.grid] origin and spacing, [[mpm.body]] min, max and surface, the min, max and
  node of [[mpm.velocity]];
- times x sqrt(s) (t* = sqrt(H0 / g)): mpm.end_time, mpm.dt, the velocities' from and until;
- velocities x sqrt(s): the imposed x, y, z of [[mpm.velocity]];
- stresses x s (rho g L0): every pressure_floor;
- [output] every x 1 / sqrt(s), rounded (the MPM step scales as the cell, s, and the run as
  sqrt(s): the same number of rows).
Everything else is copied: the DEM material and sample (the grains are the same), and a
continuum's young_modulus. --damping sets the RVEs' Cundall damping, to match a pure-DEM
reference; --young-modulus sets the grains' contact modulus (dem.material.young_modulus) and
scales dem.preparation.pressure by the same factor (the same stiffness number E / p when the RVEs
are prepared), for the stiffness-number study of docs/validation/column_collapse.md; --mpm adds
[mpm] lines (a transfer or wall option of a variant); --continuum replaces the RVEs by the
Drucker-Prager continuum of [mpm.elastic] with the lines given (the [dem.*] and [farm] tables
dropped, material = "elastic", "MPM x DEM, N RVEs of M spheres" in the title becomes
"Drucker-Prager continuum"): the same column, cells and walls with a law whose strength is known.
Comments are dropped and a header naming the source and the factors is written.

Usage: tools/mpmxdem-tools column_scale_job JOB --l0 METRES --out OUT.toml [--damping D]
           [--young-modulus PA] [--mpm 'KEY = VALUE' ...] [--continuum 'KEY = VALUE' ...]
           [--tag TEXT]
       tools/mpmxdem-tools column_scale_job --check SCALED [SCALED ...]
           (exit 1 when a SCALED job is not what the command in its header writes)
       tools/mpmxdem-tools column_scale_job --self-test
"""
import argparse
import math
import re
import sys

LENGTH_KEYS = {"mpm.grid": ("origin", "spacing"), "mpm.body": ("min", "max", "surface"),
               "mpm.velocity": ("min", "max", "node")}
TIME_KEYS = {"mpm": ("end_time", "dt"), "mpm.velocity": ("from", "until")}
VELOCITY_KEYS = {"mpm.velocity": ("x", "y", "z")}
NUMBER = re.compile(r'"?(-?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)(?: ([A-Za-z/^0-9]+))?"?')
UNIT_FACTORS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "cm": 1e-2, "s": 1.0, "ms": 1e-3, "Pa": 1.0,
                "kPa": 1e3, "MPa": 1e6, "m/s": 1.0}


def fmt(x):
    return f"{x:.6g}"


def scale_values(text, factor, unit):
    """Every number of a TOML value (a number, a quantity string or a list of them) times factor,
    written as a quantity in `unit` when it was a quantity string, as a bare number otherwise."""
    def one(m):
        value = float(m.group(1))
        given = m.group(2)
        if given is not None:
            if given not in UNIT_FACTORS:
                raise ValueError(f"unit {given!r} in {text!r}: not one this tool scales")
            return f'"{fmt(value * UNIT_FACTORS[given] * factor)} {unit}"'
        return fmt(value * factor)
    return NUMBER.sub(one, text)


def si(token):
    """The value of one TOML number or quantity string ("500 mm") in SI units."""
    m = NUMBER.fullmatch(token.strip())
    if m is None or (m.group(2) is not None and m.group(2) not in UNIT_FACTORS):
        raise ValueError(f"{token!r}: not a number or a quantity this tool reads")
    return float(m.group(1)) * (UNIT_FACTORS[m.group(2)] if m.group(2) else 1.0)


def column_length(text):
    """L0 of the first [[mpm.body]]: its max x minus its min x [m]."""
    body = text[text.index("[[mpm.body]]"):]
    lo = re.search(r"^min\s*=\s*\[([^\]]*)\]", body, re.M).group(1).split(",")[0]
    hi = re.search(r"^max\s*=\s*\[([^\]]*)\]", body, re.M).group(1).split(",")[0]
    return si(hi) - si(lo)


def set_damping(text, damping):
    """`text` with [dem.numerics] damping = damping (the section added when absent)."""
    if re.search(r"^\[dem.numerics\]", text, re.M):
        if re.search(r"^damping\s*=", text[text.index("[dem.numerics]"):].split("\n[")[0], re.M):
            head, _, tail = text.partition("[dem.numerics]")
            block, sep, rest = tail.partition("\n[")
            block = re.sub(r"^damping\s*=.*$", f"damping = {damping:g}", block, count=1, flags=re.M)
            return head + "[dem.numerics]" + block + sep + rest
        return text.replace("[dem.numerics]", f"[dem.numerics]\ndamping = {damping:g}", 1)
    return text.replace("[dem.coupling]", f"[dem.numerics]\ndamping = {damping:g}\n\n[dem.coupling]", 1)


def section_value(text, section, key):
    """The value text of `key` in [section] (None when absent)."""
    m = re.search(r"^\[" + re.escape(section) + r"\]\s*$(.*?)(?=^\[|\Z)", text, re.M | re.S)
    if not m:
        return None
    v = re.search(r"^" + re.escape(key) + r"\s*=\s*([^#\n]*)", m.group(1), re.M)
    return v.group(1).strip() if v else None


def as_continuum(text, elastic):
    """`text` with its RVEs replaced by the continuum of [mpm.elastic] with the lines `elastic`:
    the [dem.*] and [farm] tables dropped, the bodies' material "elastic", the title's "MPM x DEM,
    N RVEs of M spheres" read "Drucker-Prager continuum"."""
    blocks = re.split(r"(?m)^(?=\[)", text)
    kept = [b for b in blocks
            if not re.match(r"\[(dem\.[^\]]*|farm)\]\s*(#.*)?$", b.split("\n", 1)[0].strip())]
    text = "".join(kept)
    text = re.sub(r'^(material\s*=\s*)"dem"', r'\1"elastic"', text, flags=re.M)
    text = re.sub(r"MPM x DEM, \d+ RVEs of \d+ spheres", "Drucker-Prager continuum", text)
    return re.sub(r"^\[mpm\]\s*$", "[mpm.elastic]\n" + "\n".join(elastic) + "\n\n[mpm]", text,
                  count=1, flags=re.M)


def first_in(text, section, lines, source_name="the job"):
    """`text` with `lines` added first in its table [section] (none: unchanged). ValueError when
    the job has no such table, or the table has a line's key already (a TOML duplicate: --set)."""
    if not lines:
        return text
    if not re.search(rf"^\[{re.escape(section)}\]\s*$", text, re.M):
        raise ValueError(f"no table [{section}] in {source_name} to add {lines[0]!r} to")
    for line in lines:
        key = line.partition("=")[0].strip()
        if section_value(text, section, key) is not None:
            raise ValueError(f"[{section}] of {source_name} has {key} already: --set "
                             f"'{section}.{key} = ...' replaces it")
    return re.sub(rf"^\[{re.escape(section)}\]\s*$", f"[{section}]\n" + "\n".join(lines), text,
                  count=1, flags=re.M)


def scale(text, l0_new, source_name, tag="", damping=None, young=None, mpm=(), spheres=None,
          coupling=(), sets=(), continuum=(), preparation=(), initial_state=()):
    """The job text of `text` at column length l0_new [m] (and the RVEs' Cundall damping, the
    grains' contact modulus [Pa] with the preparation pressure scaled by the same factor, the
    [mpm] lines `mpm` ("key = value", dimensionless or names: not scaled) added first in [mpm],
    the number of spheres per RVE, dem.sample.spheres, with the title's "of N spheres", and the
    [dem.coupling] lines `coupling`, the [dem.preparation] lines `preparation` (e.g. a target
    void ratio) and the [dem.initial_state] lines `initial_state` (e.g. how the points draw a pool
    of samples), added first there, not scaled; and `sets`,
    "section.key = value" lines whose value replaces that key's in the scaled job, e.g. gravity
    changed by 1e-6 for a family of runs: ValueError if the job has no such key); with
    `continuum` ([mpm.elastic] lines) the column of a Drucker-Prager continuum instead of RVEs."""
    replace = {}
    for line in sets:
        full, _, value = line.partition("=")
        section, _, key = full.strip().rpartition(".")
        entry = re.fullmatch(r"(.+)\[([^\]]+)\]", section)  # an entry of an array of tables, by its name
        replace[(entry.group(1), entry.group(2), key) if entry else (section, None, key)] = value.strip()
    used = set()
    if continuum:
        text = as_continuum(text, continuum)
    if damping is not None:
        text = set_damping(text, damping)
    for section, lines in (("mpm", mpm), ("dem.coupling", coupling), ("dem.preparation", preparation),
                           ("dem.initial_state", initial_state)):
        text = first_in(text, section, lines, source_name)
    stiffness = 1.0
    if young is not None:
        stiffness = young / si(section_value(text, "dem.material", "young_modulus"))
    s = l0_new / column_length(text)
    st = math.sqrt(s)
    out = []
    section = ""
    entry_name = None
    for raw in text.split("\n"):
        if raw.lstrip().startswith("#"):
            continue
        line = raw.split("#", 1)[0].rstrip() if not raw.lstrip().startswith("title") else raw.rstrip()
        if not line.strip():
            if out and out[-1] != "":
                out.append("")
            continue
        header = re.match(r"^\s*\[\[?([^\]]+)\]\]?\s*$", line)
        if header:
            section = header.group(1).strip()
            entry_name = None
            out.append(line.strip())
            continue
        key, _, value = line.partition("=")
        key = key.strip()
        value = value.strip()
        if key == "name":
            entry_name = value.strip('"')
        if key in LENGTH_KEYS.get(section, ()):
            value = scale_values(value, s, "m")
        elif key in TIME_KEYS.get(section, ()):
            value = scale_values(value, st, "s")
        elif key in VELOCITY_KEYS.get(section, ()):
            value = scale_values(value, st, "m/s")
        elif key == "pressure_floor":
            value = scale_values(value, s, "Pa")
        elif young is not None and section == "dem.material" and key == "young_modulus":
            value = f'"{fmt(young)} Pa"'
        elif young is not None and section == "dem.preparation" and key == "pressure":
            value = scale_values(value, stiffness, "Pa")
        elif spheres is not None and section == "dem.sample" and key == "spheres":
            value = str(spheres)
        elif section == "output" and key == "every":
            value = str(max(1, round(int(value) / st)))
        elif key == "title":
            if spheres is not None:
                value = re.sub(r"of \d+ spheres", f"of {spheres} spheres", value)
            value = value.rstrip('"') + f', L0 = {fmt(l0_new)} m{(" " + tag) if tag else ""}"'
        for target in ((section, None, key), (section, entry_name, key)):
            if target in replace:
                value = replace[target]
                used.add(target)
        out.append(f"{key} = {value}")
    missing = [f"{sec}{f'[{name}]' if name else ''}.{key}" for sec, name, key in replace
               if (sec, name, key) not in used]
    if missing:
        raise ValueError(f"--set: no key {', '.join(missing)} in {source_name}")
    head = [f"# Generated by tools/mpmxdem_tools/jobs/column_scale_job.py from {source_name}: the same column at",
            f"# L0 = {fmt(l0_new)} m (s = {fmt(s)}): lengths x s, times x sqrt(s), imposed velocities x",
            "# sqrt(s), pressure floors x s, output.every x 1/sqrt(s); the grains, the density and gravity",
            "# unchanged (docs/validation/column_collapse.md, \"At the grains' own size\").",
            f"# Do not edit: tools/mpmxdem-tools column_scale_job {source_name} --l0 {fmt(l0_new)}"
            + (f" --damping {damping:g}" if damping is not None else "")
            + (f" --young-modulus {fmt(young)}" if young is not None else "")
            + "".join(f" --mpm '{line}'" for line in mpm)
            + (f" --spheres {spheres}" if spheres is not None else "")
            + "".join(f" --coupling '{line}'" for line in coupling)
            + "".join(f" --preparation '{line}'" for line in preparation)
            + "".join(f" --initial-state '{line}'" for line in initial_state)
            + "".join(f" --set '{line}'" for line in sets)
            + "".join(f" --continuum '{line}'" for line in continuum)
            + (f" --tag '{tag}'" if tag else "") + " --out THIS_FILE"]
    while out and out[-1] == "":
        out.pop()
    return "\n".join(head + out) + "\n"


def options_of_scaled(text):
    """(source, l0, tag, damping, young, mpm lines, spheres, coupling lines, set lines, continuum
    lines, preparation lines, initial-state lines) from the header of a scaled job; None when it
    has none."""
    cmd = re.search(r"^# Do not edit: tools/mpmxdem-tools column_scale_job (\S+) (.*) --out THIS_FILE$",
                    text, re.M)
    if not cmd:
        return None
    m = re.search(r"--l0 (\S+)", cmd.group(2))
    t = re.search(r"--tag '([^']*)'", cmd.group(2))
    d = re.search(r"--damping (\S+)", cmd.group(2))
    e = re.search(r"--young-modulus (\S+)", cmd.group(2))
    n = re.search(r"--spheres (\d+)", cmd.group(2))
    return (cmd.group(1), float(m.group(1)), (t.group(1) if t else ""),
            (float(d.group(1)) if d else None), (float(e.group(1)) if e else None),
            tuple(re.findall(r"--mpm '([^']*)'", cmd.group(2))), (int(n.group(1)) if n else None),
            tuple(re.findall(r"--coupling '([^']*)'", cmd.group(2))),
            tuple(re.findall(r"--set '([^']*)'", cmd.group(2))),
            tuple(re.findall(r"--continuum '([^']*)'", cmd.group(2))),
            tuple(re.findall(r"--preparation '([^']*)'", cmd.group(2))),
            tuple(re.findall(r"--initial-state '([^']*)'", cmd.group(2))))


def self_test():
    src = """# a comment
title = "col"
[dem.material]
young_modulus = "300 MPa"
[dem.preparation]
pressure = "10 kPa"
[dem.coupling]
pressure_floor = "500 Pa"   # floor
[mpm]
end_time = "2.26 s"
dt = 1e-4
[mpm.grid]
origin = [0.0, 0.0, 0.0]
spacing = [0.0625, 0.0625, 0.0625]
cells = [32, 1, 10]
[[mpm.body]]
min = [0.0, 0.0, 0.0]
max = ["500 mm", 0.0625, 0.5]
[[mpm.velocity]]
min = [0.5, 0.0, 0.0]
x = 0.25
until = "20 ms"
[output]
every = 50
"""
    out = scale(src, 0.005, "src.toml", damping=0.05, young=3e6, mpm=('wall_impulse = "points"',))
    expect = ['pressure_floor = "5 Pa"', 'end_time = "0.226 s"', "dt = 1e-05",
              "spacing = [0.000625, 0.000625, 0.000625]", "cells = [32, 1, 10]",
              'max = ["0.005 m", 0.000625, 0.005]', "min = [0.005, 0, 0]", "x = 0.025",
              'until = "0.002 s"', "every = 500", 'title = "col, L0 = 0.005 m"',
              "[dem.numerics]", "damping = 0.05", 'young_modulus = "3e+06 Pa"',
              'pressure = "100 Pa"', 'wall_impulse = "points"']
    missing = [e for e in expect if e not in out.split("\n")]
    if missing or "comment" in out or abs(column_length(out) - 0.005) > 1e-15:
        print("self-test FAILED; missing:", missing, "\n" + out)
        return 1
    if options_of_scaled(out) != ("src.toml", 0.005, "", 0.05, 3e6, ('wall_impulse = "points"',), None,
                                  (), (), (), (), ()):
        print("self-test FAILED: the header does not name --l0")
        return 1
    more = scale('title = "a, 512 RVEs of 100 spheres"\n[dem.sample]\nspheres = 100\n' + src, 0.005,
                 "src.toml", spheres=300)
    if ("spheres = 300" not in more.split("\n") or "of 300 spheres" not in more
            or options_of_scaled(more)[6] != 300):
        print("self-test FAILED: --spheres\n" + more)
        return 1
    more = scale(src.replace("[mpm]\n", "[dem.coupling]\n[mpm]\n"), 0.005, "src.toml",
                 coupling=('contact_loss = "strained"',))
    if ('contact_loss = "strained"' not in more.split("\n")
            or options_of_scaled(more)[7] != ('contact_loss = "strained"',)):
        print("self-test FAILED: --coupling\n" + more)
        return 1
    more = scale(src, 0.005, "src.toml", preparation=("void_ratio = 0.565",)).split("\n")
    if (more[more.index("[dem.preparation]") + 1] != "void_ratio = 0.565"
            or options_of_scaled("\n".join(more))[10] != ("void_ratio = 0.565",)):
        print("self-test FAILED: --preparation\n" + "\n".join(more))
        return 1
    draw = ("samples = 16", 'sample_draw = "scattered"')
    more = scale(src + "[dem.initial_state]\ngroup_tolerance = 0.05\n", 0.005, "src.toml",
                 initial_state=draw).split("\n")
    at = more.index("[dem.initial_state]")
    if more[at + 1:at + 3] != list(draw) or options_of_scaled("\n".join(more))[11] != draw:
        print("self-test FAILED: --initial-state\n" + "\n".join(more))
        return 1
    try:
        scale(src + "[dem.initial_state]\nsamples = 1\n", 0.005, "src.toml", initial_state=("samples = 4",))
        print("self-test FAILED: --initial-state of a key the table has was accepted (a TOML duplicate)")
        return 1
    except ValueError:
        pass
    try:
        scale(src, 0.005, "src.toml", initial_state=draw)
        print("self-test FAILED: --initial-state without [dem.initial_state] in the job was accepted")
        return 1
    except ValueError:
        pass
    g = 'mpm.dt = 1.000001e-4'
    more = scale(src, 0.005, "src.toml", sets=(g,))
    if "dt = 1.000001e-4" not in more.split("\n") or options_of_scaled(more)[8] != (g,):
        print("self-test FAILED: --set\n" + more)
        return 1
    walls = src + '[[mpm.velocity]]\nname = "base"\nfriction = 10.0\n[[mpm.velocity]]\nname = "back"\nfriction = 0.0\n'
    more = scale(walls, 0.005, "src.toml", sets=("mpm.velocity[base].friction = 0.6",)).split("\n")
    at = more.index('name = "base"')
    if more[at + 1] != "friction = 0.6" or more[more.index('name = "back"') + 1] != "friction = 0.0":
        print("self-test FAILED: --set of one named entry of an array of tables\n" + "\n".join(more))
        return 1
    body = ('title = "c, MPM x DEM, 64 RVEs of 100 spheres, plane strain"\n' + src
            + '[[mpm.body]]\nmaterial = "dem"\n[farm]\nwait = "sleep"\n')
    lines = ('young_modulus = "1 MPa"', 'friction_angle = "60 deg"')
    more = scale(body, 0.005, "src.toml", continuum=lines)
    kept = more.split("\n")
    if (any(line.startswith(("[dem", "[farm", "pressure_floor", "wait")) for line in kept)
            or 'material = "elastic"' not in kept or kept[kept.index("[mpm.elastic]") + 2] != lines[1]
            or 'title = "c, Drucker-Prager continuum, plane strain, L0 = 0.005 m"' not in kept
            or options_of_scaled(more)[9] != lines):
        print("self-test FAILED: --continuum\n" + more)
        return 1
    for absent in ("mpm.velocity[top].friction = 1", "mpm.gravity = 1"):  # an entry, a key the job lacks
        try:
            scale(src, 0.005, "src.toml", sets=(absent,))
            print(f"self-test FAILED: --set '{absent}' of what the job lacks was accepted")
            return 1
        except ValueError:
            pass
    print("self-test passed")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("job", nargs="?")
    ap.add_argument("--l0", type=float, help="column length L0 of the new job [m]")
    ap.add_argument("--out")
    ap.add_argument("--tag", default="", help="appended to the title")
    ap.add_argument("--damping", type=float, default=None,
                    help="the RVEs' Cundall damping, [dem.numerics] damping (e.g. the pure-DEM "
                         "reference's 0.05); absent: the source's")
    ap.add_argument("--young-modulus", type=float, default=None, metavar="PA",
                    help="the grains' contact modulus [Pa], dem.material.young_modulus; "
                         "dem.preparation.pressure is scaled by the same factor")
    ap.add_argument("--mpm", action="append", default=[], metavar="'KEY = VALUE'",
                    help="a line added first to [mpm], not scaled (a name or a dimensionless "
                         "value, e.g. 'wall_impulse = \"points\"'); repeat for several")
    ap.add_argument("--spheres", type=int, default=None, metavar="N",
                    help="spheres per RVE, dem.sample.spheres (and the title's \"of N spheres\")")
    ap.add_argument("--coupling", action="append", default=[], metavar="'KEY = VALUE'",
                    help="a line added first to [dem.coupling], not scaled (a name or a "
                         "dimensionless value); repeat for several")
    ap.add_argument("--preparation", action="append", default=[], metavar="'KEY = VALUE'",
                    help="a line added first to [dem.preparation], not scaled (e.g. 'void_ratio = "
                         "0.565', a target void ratio of the RVEs' packing); repeat for several")
    ap.add_argument("--initial-state", action="append", default=[], metavar="'KEY = VALUE'",
                    help="a line added first to [dem.initial_state], not scaled (e.g. 'sample_draw = "
                         "\"scattered\"', a pool of RVE packings scattered over the points); a key "
                         "the table has already: --set; repeat for several")
    ap.add_argument("--set", action="append", default=[], metavar="'SECTION.KEY = VALUE'",
                    help="replace the value of a key of the scaled job (not scaled), e.g. "
                         "'mpm.gravity = [0.0, 0.0, \"-9.81001 m/s^2\"]' for a family of runs "
                         "that differ by 1e-6; an entry of an array of tables by its name: "
                         "'mpm.velocity[base].friction = 0.6'; repeat for several")
    ap.add_argument("--continuum", action="append", default=[], metavar="'KEY = VALUE'",
                    help="a line of [mpm.elastic]: the column of that Drucker-Prager continuum "
                         "instead of RVEs (the [dem.*] and [farm] tables dropped); repeat for "
                         "several, e.g. 'young_modulus = \"1 MPa\"' 'poisson_ratio = 0.3' "
                         "'friction_angle = \"60 deg\"'")
    ap.add_argument("--check", nargs="+", metavar="SCALED",
                    help="each job is what the command in its header writes (run from the "
                         "repository root)")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        return self_test()
    if args.check:
        fails = 0
        for scaled in args.check:
            have = open(scaled).read()
            options = options_of_scaled(have)
            if options is None:
                print(f"{scaled}: no 'Do not edit' line of tools/mpmxdem-tools column_scale_job in its header")
                fails += 1
                continue
            (source, l0, tag, damping, young, mpm, spheres, coupling, sets, continuum, preparation,
             initial_state) = options
            if have != scale(open(source).read(), l0, source, tag, damping, young, mpm, spheres,
                             coupling, sets, continuum, preparation, initial_state):
                print(f"{scaled}: not what tools/mpmxdem-tools column_scale_job writes from {source} at "
                      f"L0 = {l0} m; regenerate it with the command in its header")
                fails += 1
            else:
                print(f"{scaled}: up to date with {source}")
        return 1 if fails else 0
    if not (args.job and args.l0 and args.out):
        ap.error("JOB, --l0 and --out are required (or --check / --self-test)")
    if args.continuum and (args.damping is not None or args.young_modulus is not None
                           or args.spheres is not None or args.coupling or args.preparation
                           or args.initial_state):
        ap.error("--continuum replaces the RVEs: --damping, --young-modulus, --spheres, "
                 "--coupling, --preparation and --initial-state set the RVEs and do not apply")
    try:
        text = scale(open(args.job).read(), args.l0, args.job, args.tag, args.damping,
                     args.young_modulus, tuple(args.mpm), args.spheres, tuple(args.coupling),
                     tuple(args.set), tuple(args.continuum), tuple(args.preparation),
                     tuple(args.initial_state))
    except ValueError as e:
        print(f"column_scale_job.py: {e}", file=sys.stderr)
        return 2
    open(args.out, "w").write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
