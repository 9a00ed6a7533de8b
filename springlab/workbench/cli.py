"""The command line: ``springlab design my_arm.toml`` (or ``my_arm.json``, or a URDF: ``my_arm.urdf``).

Prints the ranked designs of :func:`springlab.design.rank.design_arm` as a table
and writes the chosen one (rank 1 unless ``--pick``) as JSON. With ``--sheet`` it also
realises the chosen design's springs (:mod:`springlab.design.buildable`) and writes their
spec sheet beside the JSON, as CSV (``<name>.sheet.csv``) and Markdown (``<name>.sheet.md``,
with the balance the built springs leave). With ``--csv ranked.csv`` it writes every ranked
design, one row each, for a spreadsheet.

Every argument, the arm file and the output path are checked before the search
starts. An error prints one line, ``springlab: <what is wrong and what to do>``,
and exits with status 2; a search that finds no design prints why the
configurations were rejected and exits with status 1. A URDF arm's design that fails
its own checks (:meth:`springlab.design.arms.ArmDesign.flags`: no better than its
negative control, a joint left worse than gravity alone, a spring with no line of action
at a workspace pose) is still written, its JSON's ``status`` says why, a warning line
says so and the command exits with status 3. An unexpected error (a defect in
springlab) exits with status 4. The last line printed is the wall time of the whole
command.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

from springlab.errors import LineChainError, SpringlabError, UpAdviceError


def _process_age() -> float:
    """s: how long this process has run (Linux's /proc; 0 elsewhere), so that the wall time printed counts
    the interpreter's start and the imports before this module."""
    try:
        ticks = int(Path("/proc/self/stat").read_text().rsplit(")", 1)[1].split()[19])
        uptime = float(Path("/proc/uptime").read_text().split()[0])
        return max(uptime - ticks / os.sysconf("SC_CLK_TCK"), 0.0)
    except (OSError, ValueError, IndexError):
        return 0.0


_STARTED = time.perf_counter() - _process_age()  # when the command started

EXIT_FLAGGED = 3
"""Exit status of a design written although it fails its own checks."""

EXIT_INTERNAL = 4
"""Exit status of an unexpected error (a defect in springlab)."""

TIME_LIMIT = 300.0
"""s: the default limit on the command line's search (``--time-limit``)."""


class _Parser(argparse.ArgumentParser):
    """argparse, with its errors on one line and exit status 2."""

    def error(self, message):
        self.exit(2, f"springlab: {message} (see 'springlab design --help')\n")


def _writable(path: Path, what: str) -> Path:
    """``path`` if a file can be written there, checked before any work is done."""
    if path.is_dir():
        raise SpringlabError(f"{what} {path} is a directory: give a file name")
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise SpringlabError(f"{what} {path}: the folder {parent} does not exist")
    if not os.access(parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise SpringlabError(f"{what} {path} cannot be written (permission denied): choose another path")
    return path


def _no_clash(arm_file, outputs) -> None:
    """Refuse, before any work, an output that is the arm file itself or that another output also names:
    ``outputs`` is (the flag, the path) pairs the command will write."""
    source = Path(arm_file).resolve()
    seen = {}
    for what, path in outputs:
        where = Path(path).resolve()
        if where == source:
            raise SpringlabError(f"{what} {path} is the arm file itself: writing there would replace it; give "
                                 "another file name")
        if where in seen:
            raise SpringlabError(f"{seen[where]} and {what} both name {path}: one would overwrite the other; give "
                                 "each its own file name")
        seen[where] = what


def _check_arguments(args) -> None:
    from springlab import _checks

    _checks.count("--pick", args.pick, least=1)
    _checks.count("--max-designs", args.max_designs, least=1)
    if args.max_configurations is not None:
        _checks.count("--max-configurations", args.max_configurations, least=1)
    _checks.count("--seed", args.seed)
    if args.samples is not None:
        _checks.count("--samples", args.samples, least=100, why=": the poses every share is checked on")
    if args.fit_poses is not None:
        _checks.count("--fit-poses", args.fit_poses, least=20, why=": the best springs' fit needs a few per unknown")
    if args.audit_samples is not None:
        _checks.count("--audit-samples", args.audit_samples, least=100,
                      why=": the independent poses the peaks are re-checked on")
    _checks.positive("--time-limit", args.time_limit, unit="s")
    from springlab.model.armfile import parse_quantity

    if args.pulley_radius is not None:
        args.pulley_radius = _checks.positive("--pulley-radius", parse_quantity(args.pulley_radius, "length",
                                                                                "--pulley-radius"),
                                              allow_zero=True, unit="m") + 0.0
    target = _checks.number("--target", args.target)
    if not 0 < target <= 1:
        raise SpringlabError(f"--target = {args.target!r}: give the share of each loaded joint's peak to remove, above 0 "
                             "and at most 1 (e.g. 0.9)")
    if args.cable is not None:
        from springlab.design.cables import cable_by_name

        args.cable = cable_by_name(args.cable, option="--cable")
        if args.pulley_radius and not args.cable.fits(args.pulley_radius):
            raise SpringlabError(f"--cable {args.cable.name}: --pulley-radius {1e3 * args.pulley_radius:g} mm is too "
                                 f"small for it (its D/d of {args.cable.ratio:g} asks for "
                                 f"{1e3 * args.cable.pulley_radius:g} mm); give a larger pulley or a finer cable")
    if args.margin is not None:
        args.margin = _checks.positive("--margin", parse_quantity(args.margin, "length", "--margin"),
                                       allow_zero=True, unit="m") + 0.0
    if args.share is not None:
        args.share = _checks.number("--share", args.share)
        if not 0.0 <= args.share < 1.0:
            raise SpringlabError(f"--share = {args.share:g}: give the share of the largest gravity peak below which a "
                                 "joint gets no spring, from 0 to 1 (e.g. 0.02)")
        if args.layout == "two-point":
            raise SpringlabError("--share applies to the belt and pseudobase layouts (the two-point springs balance every "
                             "loaded joint)")
    if args.layout in ("belts", "pseudobases") and args.payload_range is not None:
        raise SpringlabError(f"--payload-range applies to the two-point layout: the {args.layout} layout has no payload "
                             "dial yet")
    if args.layout == "auto" and (args.payload_range is not None or args.reach is not None):
        args.layout = "two-point"  # the payload dial moves two-point springs' anchors; --reach sets their brackets
    if args.payload is not None:
        from springlab.design.payload import MAX_PAYLOAD_RANGE
        from springlab.model.armfile import parse_quantity

        mass = parse_quantity(args.payload, "mass", "--payload")
        if not 0 <= mass <= MAX_PAYLOAD_RANGE:
            raise SpringlabError(f"--payload = {args.payload!r} ({mass:g} kg): give a payload from 0 to "
                                 f"{MAX_PAYLOAD_RANGE:g} kg, e.g. --payload '2 kg'")
    args.payloads = None if args.payload_range is None else _payload_range(args.payload_range)
    if args.pick > args.max_designs:
        raise SpringlabError(f"--pick = {args.pick} is above --max-designs = {args.max_designs}: "
                             "raise --max-designs or pick a lower rank")


def _payload_range(text: str) -> tuple[float, float]:
    """--payload-range 'LOW:HIGH' (kg; units allowed) as two checked numbers."""
    from springlab.design.payload import payload_range
    from springlab.model.armfile import parse_quantity

    parts = text.split(":")
    if len(parts) != 2:
        raise SpringlabError(f"--payload-range = {text!r}: give LOW:HIGH in kg, e.g. --payload-range 0:5")
    low, high = (parse_quantity(v.strip(), "mass", "--payload-range") for v in parts)
    return payload_range(low, high)


def _up(text):
    """--up 'x,y,z' as three numbers, or None."""
    if text is None:
        return None
    try:
        up = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        up = []
    if len(up) != 3:
        raise SpringlabError(f"--up = {text!r}: give three numbers, the up direction in the URDF's base link "
                             "frame, e.g. --up 0,0,1")
    return up


def _design(args) -> int:
    from springlab.design.rank import design_arm
    from springlab.model.armfile import load_arm

    _check_arguments(args)
    from springlab.model.armfile import is_dh_arm, read_arm_data

    path, data = read_arm_data(args.arm_file)
    if is_dh_arm(data):
        return _design_dh(args, path)
    for folder in args.package_dir:
        if not folder.strip() or not Path(folder).is_dir():
            raise SpringlabError(f"--package-dir = {folder!r} is not a folder: give the folder that holds the "
                                 "URDF's mesh packages")
    if (args.reach is not None or args.package_dir or args.margin is not None or args.layout not in ("auto", "two-point")
            or args.share is not None) and path.suffix != ".urdf":
        raise SpringlabError("--reach, --package-dir, --margin and --layout apply to URDF files (an arm file bounds "
                             "its attachments with limits: max_attachment, and has no link shapes to clear)")
    if (args.samples is not None or args.fit_poses is not None) and path.suffix != ".urdf":
        raise SpringlabError("--samples and --fit-poses apply to URDF files, designed on the general model (an arm "
                             "file gives its workspace's poses in its [workspace] table: samples = ...)")
    if args.workspace is not None and path.suffix != ".urdf":
        raise SpringlabError(f"--workspace = {args.workspace!r} applies to URDF files (an arm file gives each "
                             "joint's range in its links' 'range')")
    if args.payload_range is not None and path.suffix != ".urdf":
        raise SpringlabError(f"--payload-range = {args.payload_range!r} applies to URDF files, designed on the general "
                             "model with a payload dial (an arm file's payload is its [payload] table)")
    if args.catalog is not None and path.suffix != ".urdf":
        raise SpringlabError(f"--catalog {args.catalog}: stock parts are chosen for a URDF arm's belt or pseudobase "
                             "springs, whose ends are re-placed for a part's rate")
    if args.bom is not None and path.suffix != ".urdf":
        raise SpringlabError(f"--bom {args.bom}: the shopping list is written for a URDF arm's springs, their parts "
                             "placed on its links (an arm file's springs are on its --sheet)")
    if path.suffix == ".urdf" and (args.bom is not None or args.workspace is not None or args.reach is not None
                                   or args.catalog is not None
                                   or args.package_dir
                                   or args.payload_range is not None or args.margin is not None
                                   or args.layout != "auto" or args.share is not None
                                   or args.samples is not None or args.fit_poses is not None):
        return _design_general(args, path, data, "")  # ranges, reaches and outlines: the general model's
    try:
        spec = load_arm(args.arm_file, allow_large=args.allow_large, up=_up(args.up), tip=args.tip, base=args.base,
                        payload=args.payload)
    except LineChainError as err:  # an offset shoulder, a centre of mass off its link, ...: the general model
        return _design_general(args, path, data, str(err))
    except UpAdviceError as err:  # another up reads it as a line chain: only an up the user gave is trusted
        if args.up is None:
            raise
        return _design_general(args, path, data, str(err))
    out = _writable(Path(args.json or Path(args.arm_file).with_suffix(".design.json").name), "--json")
    if args.sheet:
        for path in _sheet_paths(out):
            _writable(path, "--sheet")
    mjcf = _mjcf_paths(args)
    if args.csv:
        _writable(Path(args.csv), "--csv")
    _no_clash(args.arm_file, [("--json", out), *(("--sheet", p) for p in (_sheet_paths(out) if args.sheet else ())),
                              *(("--mjcf", p) for p in mjcf), *((("--csv", args.csv),) if args.csv else ())])
    report = design_arm(spec, method=args.method, max_designs=args.max_designs,
                        max_configurations=args.max_configurations, seed=args.seed, progress=not args.quiet,
                        time_limit=args.time_limit)
    carried = f"; {args.payload} at the tip frame, in link {spec.n}'s mass" if args.payload else ""
    print(f"# {spec.name}: n = {spec.n} links (ground included), payload {spec.payload:g} kg{carried}")
    for note in report.notes:
        print(f"note: {note}")
    print(f"{report.configurations_tried} configurations tried in {report.seconds:.1f} s, "
          f"{len(report.designs)} verified designs, {len(report.rejected)} rejected; the search stopped: "
          f"{report.stopped}\n")
    if not report.designs:
        tried = (f"; why the {len(report.rejected)} configurations were rejected:" if report.rejected
                 else "; no configuration was reached")
        print(f"springlab: no design found ({report.stopped}){tried}", file=sys.stderr)
        for count, why in report.reasons():
            print(f"  {count} x {why}", file=sys.stderr)
        if "time limit" in report.stopped:
            print("  raise --time-limit" + (", or try --method 'ground springs' (one design for any n)"
                                           if args.method != "ground springs" else ""), file=sys.stderr)
        return 1
    print(report.table())
    if args.csv:
        try:
            Path(args.csv).write_text(report.csv())
        except OSError as err:
            raise SpringlabError(f"--csv {args.csv} cannot be written ({err.strerror})") from None
        print(f"\nevery ranked design written to {args.csv}")
    if args.pick > len(report.designs):
        raise SpringlabError(f"--pick = {args.pick} but only {len(report.designs)} designs were found: "
                             f"pick one of 1..{len(report.designs)}")
    chosen = report.designs[args.pick - 1]
    try:
        out.write_text(json.dumps({"arm": spec.name, "source": str(args.arm_file), "rank": args.pick}
                                  | chosen.to_dict(), indent=1) + "\n")
    except OSError as err:
        raise SpringlabError(f"--json {out} cannot be written ({err.strerror})") from None
    print(f"\ndesign {args.pick} written to {out}")
    if args.sheet:
        _write_sheet(args, spec, chosen, out)
    if mjcf:
        from springlab.model.chain import point_springs

        chain = spec.chain()
        _write_mjcf(mjcf, chain.revolute_chain(spec.name), point_springs(chain, chosen.springs), None)
    return 0


def _design_general(args, path: Path, text: str, why: str) -> int:
    """A URDF arm on the general model (springlab.design.arms): its structure, exact or best springs,
    their realisation and the torques they leave, printed; the design written as JSON."""
    import numpy as np

    from springlab import _checks
    from springlab.design.arms import design_model, parse_workspace, workspace_ranges
    from springlab.model.armfile import parse_quantity
    from springlab.model.urdf import read_revolute_chain

    if args.payload_range is not None and not args.tip:
        raise SpringlabError(f"--payload-range = {args.payload_range!r}: a payload is carried at the tip frame: give "
                             "the tip link too (--tip LINK)")
    payload = None if args.payload is None else parse_quantity(args.payload, "mass", "payload")
    model = read_revolute_chain(text, source=str(path), up=_up(args.up), tip=args.tip, base=args.base,
                                payload=payload, folder=path.parent, package_dirs=args.package_dir)
    workspace = None if args.workspace is None else parse_workspace(args.workspace)
    catalogue = None if args.catalog is None else _catalogue(args.catalog)  # read and checked before any work
    out = _writable(Path(args.json or path.with_suffix(".design.json").name), "--json")
    if args.sheet:
        for sheet_path in _sheet_paths(out):
            _writable(sheet_path, "--sheet")
    bom = None if args.bom is None else _writable(Path(args.bom), "--bom")
    if bom is not None and bom.suffix.lower() != ".csv":  # a list for a spreadsheet, never over another kind of file
        raise SpringlabError(f"--bom {bom}: the shopping list is a CSV file: give a name ending in .csv")
    mjcf = _mjcf_paths(args)
    _no_clash(path, [("--json", out), *(("--sheet", p) for p in (_sheet_paths(out) if args.sheet else ())),
                     *(("--mjcf", p) for p in mjcf), *((("--bom", bom),) if bom else ())])
    started = time.perf_counter()
    reach = None if args.reach is None else _checks.positive(
        "--reach", parse_quantity(args.reach, "length", "--reach"), allow_zero=True, unit="m") + 0.0
    design = design_model(model, workspace=workspace, seed=args.seed + 1, samples=args.samples or 2000,
                          fit_poses=args.fit_poses or 300, material=args.material, reach=reach,
                          pulley_radius=args.pulley_radius, margin=args.margin, layout=args.layout, share=args.share,
                          cable=args.cable, catalogue=catalogue,
                          **({"audit_samples": args.audit_samples} if args.audit_samples else {}))
    seconds = time.perf_counter() - started
    tip = (f"the tip {args.tip!r} (fixed to {model.bodies[-1]!r}, the last body a joint moves)"
           if args.tip and args.tip != model.bodies[-1] else repr(model.bodies[-1]))
    reached = design.reached(args.target) if design.structure.loaded else None
    print(f"# {model.name}: {model.n} revolute joints from {model.bodies[0]!r} to {tip}"
          + (f", payload {payload:g} kg at the tip frame" if payload else "") + _reached_line(reached)
          + _collision_line(design))
    ranges = workspace_ranges(model, workspace)
    print("workspace (deg): " + ", ".join(f"{name} {np.degrees(lo):.0f}..{np.degrees(hi):.0f}"
                                         for name, (lo, hi) in zip(model.joints, ranges, strict=True))
          + (" (the URDF limits; a full turn where unlimited)" if workspace is None else ""))
    if why:
        print(f"note: springlab's line-chain methods (paper 000) do not take this arm ({why}); designed on the "
              "general model, from the URDF's own frames")
    for note in design.notes:
        print(f"note: {note}")
    print()
    print(design.structure.table())
    if design.method == "nothing to balance":
        print("\nnothing to balance: no file written")
        return 0
    checked = design.q.shape[0] - (0 if design.audit is None else len(design.audit.worst))
    print(f"\n{design.method}: {len(design.ideal)} springs (searched, realised and checked in {seconds:.1f} s); "
          + (design.audit.note(checked) if design.audit else f"checked by route 2 on {checked} random poses") + "\n")
    print(design.table())
    by_joint = design.control_by_joint()
    print("\nnegative control: the same springs at 0.9 of their rates leave, at worst over the poses, "
          + ", ".join(f"{j} {scaled:.3g} N m (as designed {designed:.3g})" for j, (designed, scaled) in by_joint.items())
          + "\n")
    print(design.springs_table())
    print("\nwhat the realisation changed, per spring (a realised spring keeps the name of the ideal one it realises):")
    print(design.changes_table())
    if design.realised and design.clearance is not None:
        print(f"\nclearance of the realised springs (coil, cable) from the links' own shapes (coal), over the "
              f"{design.clearance.poses:,} check poses; {design.workspace}:")
        print(design.clearance.table(design.q))
        _print_narrowed(design)
    elif design.realised and model.outline:
        print(f"\nclearance of the realised springs from the bodies (their outlines), over "
              f"{min(len(design.q), 100)} workspace poses:")
        print(design.clearance_table())
    if design.realised:
        print("\nthe parts (springs, cables, pulleys, posts, belts): their sizes, masses and the largest loads over the "
              "check poses, each carried in the balance where it rides:")
        print(design.parts_table())
    if catalogue is not None and design.realised:
        print(f"\nthe stock parts ({len(catalogue)} in {catalogue.source}): each spring's part, and its working range "
              "over the check poses against the catalogue's largest extension and load:")
        print(design.stock_table())
    if reached is not None and not reached["reached"] and design.realised:
        print(f"\nthe target, {100 * args.target:g} % of each loaded joint's peak, is missed at "
              f"{', '.join(reached['missed'])}; what fewer springs reach (each left out where it costs least; "
              "a stiffer target needs another layout, --workspace or --target):")
        print(design.trade_off())
    print("\nthe balance the built springs leave, with a maker's tolerances on every spring at once (route 2):")
    print(design.tolerance_table())
    if design.realised:
        print("\nwhich tolerance costs the balance most, each spring's alone (the others as specified), and the band "
              "that keeps it within a point of the springs as specified:")
        print(design.tolerance_ranking())
    study = None
    if args.tip and design.ideal:
        from springlab.design.arms import ends_outside
        from springlab.design.payload import payload_study
        from springlab.design.structure import BRACKET

        nominal = payload or 0.0
        low, high = args.payloads or (0.0, nominal + 1.0)
        masses = sorted({low + 0.0, high + 0.0, nominal} | ({nominal + 1.0} if nominal + 1.0 <= high else set()))
        dial_reach = reach
        if design.carried:  # belts or pseudobases: the springs stand beside the links, their slots within the
            # envelope their brackets already span (the farthest end from its link's box, and a bracket more)
            dial_reach = ends_outside(design.model, (*design.ideal, *design.realised), 0.0) + BRACKET
        study = payload_study(design, args.tip, masses, nominal=nominal, reach=dial_reach)
        _print_dial(study)
    inputs = {"tip": args.tip, "base": model.bodies[0], "payload_kg": payload,
              "payload_range_kg": None if args.payloads is None else list(args.payloads), "up": _up(args.up) or [0.0, 0.0, 1.0],
              "workspace_deg": {name: [float(np.degrees(lo)), float(np.degrees(hi))]
                                for name, (lo, hi) in zip(model.joints, workspace_ranges(model, workspace), strict=True)},
              "reach_m": reach, "pulley_radius_m": args.pulley_radius,
              "cable": None if args.cable is None else args.cable.name, "package_dirs": list(args.package_dir),
              "layout": args.layout, "share": args.share, "margin_m": args.margin,
              "seed": args.seed + 1,
              "material": args.material, "catalog": None if catalogue is None else catalogue.source}
    try:
        extra = ({} if study is None else {"payload": study.as_dict()}) | (
            {} if reached is None else {"target": reached | (
                {} if reached["reached"] or not design.realised else {"trade_off": design.trade_off().records()})})
        out.write_text(json.dumps({"source": str(path), "inputs": inputs} | design.as_dict() | extra, indent=1,
                                  allow_nan=False) + "\n")
    except OSError as err:
        raise SpringlabError(f"--json {out} cannot be written ({err.strerror})") from None
    print(f"\ndesign written to {out}")
    if args.sheet:
        _write_general_sheet(args, path, design, study, out)
    if bom is not None:
        from springlab.design.buildable import table_csv

        try:
            bom.write_text(table_csv(design.bom()))
        except OSError as err:
            raise SpringlabError(f"--bom {bom} cannot be written ({err.strerror})") from None
        print(f"shopping list written to {bom}")
    if mjcf:
        _write_mjcf(mjcf, design.model, design.ideal, design.realised)
    flags = design.flags()
    if not flags:
        clear = ("every spring clear of every link by the margin" if design.clearance is not None else
                 "the springs' clearance from the links is not among these checks (no link shapes): see its table")
        print("\nstatus: passed (better than its negative control; no joint left worse than gravity alone; every "
              f"spring with a line of action at every pose checked, no cable's end crossing its pulley's lead; every "
              "cable within its working load over a pulley its rope maker allows; every coil within its room (between its pulley and its joint, or on its bracket); "
              f"{clear})")
        return 0
    print(f"\nstatus: flagged, {len(flags)} of the design's own checks fail:")
    for flag in flags:
        print(f"  - {flag}")
    print(f"springlab: warning: the design fails {len(flags)} of its own checks (listed under 'status', and in {out}'s "
          f"\"status\"); the files are written; exit status {EXIT_FLAGGED}", file=sys.stderr)
    return EXIT_FLAGGED


def _collision_line(design) -> str:
    """The first line's end where a realised spring runs into a link: which, by how much, and where to look."""
    failing = design.clearance.failing() if design.realised and design.clearance is not None else ()
    if not failing:
        return ""
    worst = min(failing, key=lambda r: r[4])
    best = max(design.narrowed, key=lambda n: n.kept, default=None)
    clear = (f"on a narrower workspace they clear ({best.workspace(design.model)}, {100 * best.kept:.0f} % of it kept): "
             "see below" if best is not None else "no narrower workspace found where they clear: see below")
    return (f"; SPRINGS COLLIDE: {', '.join(r[0] for r in failing)} come within the {1e3 * design.clearance.margin:g} "
            f"mm margin of a link (at worst {worst[0]}'s {worst[1]}, {1e3 * worst[4]:.0f} mm, {worst[2]}); {clear}")


def _print_narrowed(design) -> None:
    """Where the realised springs run into a link: the narrower workspaces on which they clear, or that none was
    found."""
    if not design.clearance.failing():
        return
    if not design.narrowed:
        print("\nno narrowing of one joint's range, or of two together, that keeps a tenth of the workspace clears the "
              "springs: another layout, or the ranges the arm's task needs (--workspace)")
        return
    print("\nthe same springs (not re-designed) clear the links on a narrower workspace: the ranges of one joint, or of "
          "two, that hold none of the check poses where a spring comes within the margin and the most of the others, "
          "each re-measured on fresh poses of it (coal) with the share each loaded joint's peak keeps removed there; "
          "give it as --workspace to design for it:")
    print(design.narrowed_table())


def _reached_line(reached) -> str:
    """The first line's end: whether the design reaches its target share of each loaded joint's peak."""
    if reached is None:
        return ""
    shares = ", ".join(f"{n} {v:.1f} %" for n, v in reached["removed_percent"].items() if n not in reached["light"])
    if reached["reached"]:
        return f"; target {100 * reached['share']:g} % reached ({shares} of the peaks removed, hardware carried)"
    return (f"; TARGET MISSED: {100 * reached['share']:g} % asked, {shares} removed (hardware carried): "
            "see the trade-off below")


def _print_dial(study) -> None:
    dial, built = study.dials["ideal"], study.dials["realised"]
    print()
    if study.usable("ideal"):
        lo, hi = study.holds["ideal"]
        print(f"payload dial ({'exact' if dial.exact else 'not exact'}: {dial.how}); it keeps every moved end on its "
              f"link from {lo:.3g} to {hi:.3g} kg; per kg of payload at {study.frame!r}, move:")
        print(dial.table(study.names["ideal"]))
    if study.usable("realised"):
        lo, hi = study.holds["realised"]
        print(f"the built springs' own dial ({built.how}; linearised: {100 * built.left:.2g} % of each kilogram's torque "
              f"left; it keeps every moved end on its link from {lo:.3g} to {hi:.3g} kg):")
        print(built.table(study.names["realised"]))
    print(f"checked by route 2 at {', '.join(f'{m:g}' for m in study.masses)} kg (design made for {study.nominal:g} kg), "
          "on the design's poses (its random ones and the worst its independent check found at the nominal payload; "
          "the other payloads are not re-checked on that sample):")
    print(study.table())
    for warning in study.warnings():
        print(f"note: {warning}")


def _dial_markdown(study) -> str:
    """The sheet's section on the payload dial."""
    ideal, realised = study.dials["ideal"], study.dials["realised"]
    outside = ", ".join(f"{m:g} kg: {1e3 * d:.0f} mm" for m, d in zip(study.masses, study.outside, strict=True))
    holds = "; ".join(f"{which}: {round(lo, 3):g} to {round(hi, 3):g} kg" for which, (lo, hi) in study.holds.items()
                      if study.usable(which))
    warnings = "".join(f"- {w}\n" for w in study.warnings())
    dials = (f"{'Exact' if ideal.exact else 'Not exact'}: {ideal.how}. For each kilogram more, move (each end in its "
             f"link's URDF frame; fewer kilograms, the other way):\n\n{ideal.table(study.names['ideal']).markdown()}\n\n"
             f"How far the ideal dial takes the moved ends outside their links' boxes: {outside}.\n\n"
             if study.usable("ideal") else f"{study.refusal('ideal')}.\n\n")
    dials += (f"The built springs' own moves ({realised.how}; linearised, they leave {100 * realised.left:.2g} % of each "
              f"kilogram's torque):\n\n{realised.table(study.names['realised']).markdown()}\n\n"
              if study.usable("realised") else f"{study.refusal('realised')}.\n\n")
    dials += f"The dials keep every moved end on its link over: {holds}.\n\n" if holds else ""
    return (f"\n## Payload dial\n\nDesigned for {study.nominal:g} kg at the origin of {study.frame!r}. {dials}"
            f"Checked by route 2 (peak holding torque over the workspace poses, N m):\n\n{study.table().markdown()}\n"
            + (f"\n{warnings}" if warnings else ""))


def _write_general_sheet(args, path: Path, design, study, out: Path) -> None:
    """The spec sheet of a design on the general model: the springs for the maker, the balance they
    leave with the maker's tolerances, their clearance, and the payload dial (with --tip)."""
    from springlab.design import buildable

    csv_path, md_path = _sheet_paths(out)
    clearance = (f"\n## Clearance from the links\n\nOver {min(len(design.q), 100)} workspace poses, each spring's "
                 "distance from the links it is not attached to (their outlines; negative: it passes through one)."
                 f"\n\n{design.clearance_table().markdown()}\n") if design.model.outline else ""
    md = (f"# Spring spec sheet: {design.model.name} ({path.name})\n\n{design.method}; checked by route 2 on "
          f"{design.q.shape[0]} workspace poses. Ends in mm in their links' URDF frames; lengths in mm, forces in N, "
          f"stresses in MPa. {buildable.SHEET_NOTE}\n\n{design.sheet().markdown()}\n\n"
          "A cable spring's coil is mounted on link A; its cable runs from the coil over a pulley at end A (of the "
          "radius given) to end B. The lead is the unit direction, in link A's frame, along which the cable arrives "
          "at the pulley from the coil. The cable is cut so that, with the coil's free length and initial tension, "
          "the force is the rate times the cable's path over the pulley to B (route 2's cable path; the cable offset is L0 - Fi/k). Free "
          "lengths are measured inside the hooks.\n\n"
          "## Balance the built springs leave (route 2)\n\nPer loaded joint, the percentage of its peak gravity "
          "torque removed; each tolerance at its limit on every spring at once.\n\n"
          f"{design.tolerance_table().markdown()}\n\n"
          + ("" if not design.realised else "Which spring's tolerance costs the balance most, each spring's alone (the "
             "others as specified), and the band that keeps it within a point of the springs as specified:\n\n"
             f"{design.tolerance_ranking().markdown()}\n\n")
          + "## What the realisation changed\n\nEach realised spring keeps "
          f"the name of the ideal spring it realises.\n\n{design.changes_table().markdown()}\n"
          f"{clearance}" + ("" if study is None else _dial_markdown(study))
          + "\n## Notes\n\n" + "".join(f"- {note}\n" for note in design.notes)
          + "- the coils are sized for the nominal payload's workspace; the clearance and the room along the links "
            "are for the engineer to check (negative clearance: the spring passes through that link)\n")
    for target, text in ((csv_path, buildable.table_csv(design.sheet())), (md_path, md)):
        try:
            target.write_text(text)
        except OSError as err:
            raise SpringlabError(f"--sheet: {target} cannot be written ({err.strerror})") from None
    print(f"spec sheet written to {csv_path} and {md_path}")


def _mjcf_paths(args) -> tuple:
    """--mjcf's two files (the ideal springs; the realised ones beside it), checked before any work."""
    if not args.mjcf:
        return ()
    ideal = _writable(Path(args.mjcf), "--mjcf")
    if ideal.suffix.lower() != ".xml":
        raise SpringlabError(f"--mjcf {ideal}: give a file name ending in .xml (MuJoCo's MJCF)")
    return ideal, _writable(ideal.with_suffix(".realised.xml"), "--mjcf")


def _write_mjcf(paths, model, ideal, realised) -> None:
    """The arm and its springs as MuJoCo models: the ideal springs, and the realised ones where given."""
    from springlab.model.mjcf import to_mjcf

    texts = [(paths[0], to_mjcf(model, ideal), "ideal springs")]
    if realised is not None:
        texts.append((paths[1], to_mjcf(model, realised), "realised springs"))
    for where, text, what in texts:
        try:
            where.write_text(text)
        except OSError as err:
            raise SpringlabError(f"--mjcf {where} cannot be written ({err.strerror})") from None
        print(f"MuJoCo model with the {what} written to {where}")


def _design_dh(args, path: Path) -> int:
    """A DH arm file: paper 001's pseudobase design (one spring per module, l_CB from its equilibrium condition),
    checked by route 2 over random joint angles, printed and written as JSON (and --csv)."""
    import numpy as np

    from springlab.mechanisms.pseudobase import geometry
    from springlab.mechanisms.pseudobase.armfile import load_dh_arm
    from springlab.tables import Table

    if args.mjcf:
        raise SpringlabError(f"--mjcf writes a chain of revolute joints with springs between points of its links; "
                             f"{path} is designed by paper 001's pseudobase method, whose springs ride on "
                             "parallelogram auxiliary links (RSSR modules) that springlab does not export: leave out --mjcf")
    for flag, given in (("--sheet", args.sheet), ("--bom", args.bom), ("--catalog", args.catalog), ("--up", args.up), ("--tip", args.tip), ("--base", args.base),
                        ("--payload", args.payload), ("--method", args.method != "fewest springs"),
                        ("--reach", args.reach), ("--package-dir", args.package_dir), ("--workspace", args.workspace),
                        ("--payload-range", args.payload_range)):
        if given:
            raise SpringlabError(f"{flag} applies to arms for paper 000's method; {path} describes its arm by DH "
                                 "frames, designed by paper 001's pseudobase method")
    dh = load_dh_arm(path)
    out = _writable(Path(args.json or path.with_suffix(".design.json").name), "--json")
    if args.csv:
        _writable(Path(args.csv), "--csv")
    _no_clash(path, [("--json", out), *((("--csv", args.csv),) if args.csv else ())])
    springs = dh.design()
    q = np.random.default_rng(args.seed).uniform(-np.pi, np.pi, (2000, dh.arm.n))
    energy = geometry.energies(dh.arm, springs, q)
    share = float(np.ptp(energy["total"]) / np.ptp(energy["gravity"]))
    print(f"# {dh.name}: {dh.arm.n} DH frames, modules on links {', '.join(map(str, dh.arm.modules))} "
          f"(paper 001's pseudobase method)")
    print(f"route 2: the total energy varies by {share:.1e} of gravity's range over 2000 random poses\n")
    rows = [(sp.link, f"{sp.K:g}", f"{sp.l_CA:g}", f"{sp.l_CB:.4f}", np.round(sp.b, 4).tolist(), np.round(sp.c, 4).tolist())
            for sp in springs]
    print(Table(["spring (link)", "K (N/m)", "l_CA (m)", "l_CB (m)", "b_i in frame i (m)", "c_i in frame i (m)"], rows))
    record = {"arm": dh.name, "source": str(path), "method": "pseudobases (paper 001)", "energy_variation": share,
              "springs": [{"link": sp.link, "K_N_per_m": sp.K, "l_CA_m": sp.l_CA, "l_CB_m": sp.l_CB,
                           "b_m": sp.b.tolist(), "c_m": sp.c.tolist()} for sp in springs]}
    try:
        out.write_text(json.dumps(record, indent=1) + "\n")
        if args.csv:
            head = [f"spring{k}_{x}" for k in range(1, len(springs) + 1)
                    for x in ("link", "K_N_per_m", "l_CA_m", "l_CB_m", "bx_m", "by_m", "bz_m")]
            row = [v for sp in springs for v in (sp.link, repr(sp.K), repr(sp.l_CA), repr(sp.l_CB), *map(repr, sp.b))]
            Path(args.csv).write_text(",".join(["energy_variation", *head]) + "\n" + ",".join([repr(share), *map(str, row)]) + "\n")
    except OSError as err:
        raise SpringlabError(f"{out} or {args.csv} cannot be written ({err.strerror})") from None
    print(f"\nthe design written to {out}" + (f" and {args.csv}" if args.csv else ""))
    return 0


def _sheet_paths(out: Path) -> tuple[Path, Path]:
    stem = out.name[:-len(".design.json")] if out.name.endswith(".design.json") else out.stem
    return out.with_name(stem + ".sheet.csv"), out.with_name(stem + ".sheet.md")


def _write_sheet(args, spec, chosen, out: Path) -> None:
    from springlab.design import buildable
    from springlab.design.rank import workspace_poses

    chain = spec.chain()
    X = workspace_poses(spec, chain)
    built = buildable.realise(chain, chosen.springs, X, material=buildable.wires(args.material)[0],
                              pulley_radius=buildable.PULLEY_RADIUS if args.pulley_radius is None else args.pulley_radius)
    loss = buildable.balance_loss(chain, built, X)
    from springlab.design.clearance import clearance
    from springlab.design.rank import workspace_note

    gaps = clearance(chain, [r.spring for r in built], X, link_radii=spec.link_radii,
                     spring_radii=buildable.line_radii(built))
    csv_path, md_path = _sheet_paths(out)
    notes = [f"- {r.spring.label}: {r.kind}" + (f" (no zero-length spring: {r.note})" if r.note else "") for r in built]
    md = (f"# Spring spec sheet: {spec.name}, design {args.pick} ({chosen.label()})\n\n"
          f"{workspace_note(spec).replace('workspace', 'Workspace', 1)}. Lengths in mm, forces in N, stresses in MPa; "
          f"a, b locate each end on its link (springlab.model.springs). {buildable.SHEET_NOTE}\n\n"
          f"{buildable.spec_sheet(built).markdown()}\n\n"
          + "\n".join(notes) + "\n\n## Balance the built springs leave (route 2)\n\n"
          f"Gravity's own largest holding torque (no springs): {loss.gravity:.3g} N m.\n\n{loss.table().markdown()}\n"
          f"\n## Clearance from the links\n\nOver the same poses ({workspace_note(spec)}); links of radius "
          f"{', '.join(f'{x * 1e3:g}' for x in spec.link_radii)} mm (links 2..n).\n\n"
          f"{gaps.table().markdown()}\n")
    try:
        csv_path.write_text(buildable.sheet_csv(built))
        md_path.write_text(md)
    except OSError as err:
        raise SpringlabError(f"--sheet: {csv_path} cannot be written ({err.strerror})") from None
    print(loss.table())
    print(f"spec sheet written to {csv_path} and {md_path}")


EPILOG = """\
what a URDF arm's output says:
  the first line: whether the realised springs, carrying their hardware, remove --target of each
  loaded joint's peak (light joints aside); a missed target prints what fewer springs reach; springs
  that come within --margin of a link say so too, with the narrower workspace (one joint's range, or
  two joints') on which the same springs clear, re-measured on fresh poses of it.
  the layout: belts (a level reference carried by 1:1 belts to each joint of a planar chain, one
  spring per link beside the links, its coil along the link) where the arm allows them, else
  pseudobases (paper 001: a vertical line carried to each joint by spatial parallelogram RSSR
  modules, one spring per loaded link's subsystem), or springs between two links' points
  (--layout); the workspace is the poses within the limits where no two
  links collide and none passes below the mounting plane, its share of the limits' box printed; each
  realised spring's coil and cable are measured against the links' own collision shapes (coal) and
  must keep --margin from them; each cable is a stocked stainless rope that carries its pull five
  times over, on a pulley its rope maker allows (D/d), and a coil too long for its link runs over a
  pulley block (2:1 to 4:1); the parts table lists every coil, rope, pulley, post and belt with its
  mass and loads, and the torque tables also show the arm carrying them.
  the best springs' note lists, after each spring the greedy search added, the share of the
  worst joint's scale removed ("1 spring 0.0 %, 2 springs 36.1 %, ..."): a joint's scale is its own
  peak gravity torque, or a tenth of the arm's largest for a light joint; the search stops when
  every joint is within the target (a tenth of its scale) or at its spring limit.
  every peak and share is checked by route 2 on the design's random poses, then re-checked on
  20,000 independent ones with a local search from the worst of them; the worst poses found join
  the check, so the tables hold on them.

exit status: 0 a design that passes its own checks; 1 no design found; 2 bad input (one line
  naming it, nothing written); 3 a design written that fails its own checks (its JSON's "status"
  says which: no better than its negative control, a joint worse than gravity alone, a spring
  with no line of action at a pose, a spring nearer a link than the margin, a rope past its working
  load or on too small a pulley, a coil reaching past its joint); 4 an unexpected error (a defect:
  rerun with --debug).
  The last line printed is the wall time of the whole command.
"""


SHIPPED_CATALOGUE = ""
"""``--catalog`` given no file: springlab ships no vendor's catalogue yet, so it says to give one."""


def _catalogue(given: str):
    """The catalogue ``--catalog`` names (:func:`springlab.design.catalogue.read_catalogue`), refused in one line."""
    if given == SHIPPED_CATALOGUE:
        raise SpringlabError("--catalog: springlab ships no vendor's catalogue of stock springs yet; give your "
                             "supplier's stock list as --catalog FILE.csv (its format is in the README)")
    from springlab.design.catalogue import read_catalogue

    return read_catalogue(given)


def main(argv=None) -> int:
    started = _STARTED if argv is None else time.perf_counter()  # a console run: from its start
    parser = _Parser(prog="springlab", description="Spring gravity balancing of robot arms.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    p = sub.add_parser("design", help="rank verified spring designs for an arm file (.toml or .json)", epilog=EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("arm_file")
    p.add_argument("--json", help="where to write the chosen design (default: <arm>.design.json here)")
    p.add_argument("--pick", type=int, default=1, help="which ranked design to write (default 1)")
    p.add_argument("--method", default="fewest springs", choices=("fewest springs", "no auxiliary links", "ground springs"),
                   help="every family ranked together, fewest springs first (default); paper 000's configurations; "
                        "or n - 1 springs from the base column")
    p.add_argument("--max-designs", type=int, default=10, help="stop after this many verified designs (default 10)")
    p.add_argument("--max-configurations", type=int, default=None, help="stop after this many configurations")
    p.add_argument("--seed", type=int, default=0, help="seed of the random starts (default 0)")
    p.add_argument("--time-limit", type=float, default=TIME_LIMIT,
                   help=f"stop the search after this many seconds (default {TIME_LIMIT:g})")
    p.add_argument("--csv", help="also write every ranked design to this CSV file (one row a design)")
    p.add_argument("--sheet", action="store_true",
                   help="also write the built springs' spec sheet beside the JSON (.sheet.csv, .sheet.md)")
    p.add_argument("--bom", metavar="FILE.csv",
                   help="URDF arms only: also write the shopping list (a .csv file, replaced if it exists), each part "
                        "with its quantity, what to buy, the link it rides on and where (the springs' and cables' ends "
                        "too)")
    p.add_argument("--catalog", nargs="?", const=SHIPPED_CATALOGUE, default=None, metavar="FILE.csv",
                   help="make each spring of stock parts from this catalogue of extension springs where some fit, "
                        "their ends re-placed for the parts' rates (else wound to order); the CSV format is in the "
                        "README and springlab.design.catalogue")
    p.add_argument("--material", default="auto", choices=("auto", "music wire", "chrome silicon", "stainless 302"),
                   help="spring wire (default auto: music wire, and for a URDF arm's coils chrome silicon where that "
                        "saves a side-by-side coil or a pulley block; an arm file's --sheet: music wire)")
    p.add_argument("--layout", default="auto", choices=("auto", "two-point", "belts", "pseudobases"),
                   help="a URDF arm's springs: 'belts' (a planar chain: one spring per loaded link, from a post on a "
                        "level frame a 1:1 belt carries to its joint, its coil along the link), 'pseudobases' (any "
                        "arm: paper 001's RSSR modules keep a vertical post at each joint, one spring per loaded "
                        "link's subsystem), 'two-point' (between two links' points, exact for a planar chain) or "
                        "'auto' (default: belts where the loaded joints form a planar chain, else pseudobases; "
                        "two-point with --payload-range or --reach, or without link shapes)")
    p.add_argument("--share", type=float, default=None,
                   help="with the belt or pseudobase layout: joints whose gravity peak is below this share of the largest get no "
                        "spring (default 0.02); the torque they keep is named")
    p.add_argument("--margin", default=None,
                   help="the clearance every realised spring's coil and cable keeps from the URDF's links, e.g. '5 mm' "
                        "(a bare number is in m; default 0.005); a spring nearer than it is flagged")
    p.add_argument("--pulley-radius", default=None,
                   help="the pulley of a spring realised as a cable over a pulley, to the cable's centre, e.g. '20 mm' "
                        "(a bare number is in m; 0 for a point). Default: the belt layout's pulleys sized to their "
                        "cables (the rope maker's D/d), the two-point springs' to the cable of the largest pull; --sheet's 0.01")
    p.add_argument("--target", type=float, default=0.9,
                   help="the share of each loaded joint's peak gravity torque the realised springs, carrying their "
                        "hardware, must remove (default 0.9); a design that misses it says so in its first line and "
                        "offers what fewer springs reach")
    p.add_argument("--samples", type=int, default=None,
                   help="a URDF arm, on the general model: the random poses of the workspace every torque, share and "
                        "clearance is checked on (default 2000; --audit-samples more re-check the peaks either way); "
                        "fewer is faster")
    p.add_argument("--audit-samples", type=int, default=None,
                   help="a URDF arm: the independent random poses every peak is re-checked on, with a local search from "
                        "the worst (default 20,000); fewer is faster")
    p.add_argument("--fit-poses", type=int, default=None,
                   help="a URDF arm, on the general model: the poses the best springs are fitted on where the loaded "
                        "joints are not a planar chain (default 300)")
    p.add_argument("--cable", default=None,
                   help="the belt or pseudobase layout's cable, by its diameter in mm, e.g. '1.59' (default: the stocked stainless "
                        "rope that carries each spring's pull with a safety factor of 5, over the least pulley)")
    p.add_argument("--up", help="a URDF arm's up direction in its base link's frame, e.g. 0,1,0 (default 0,0,1: "
                                "URDF's gravity acts along -z)")
    p.add_argument("--tip", help="a URDF arm's last link: the joints from the base to it are the arm; every other "
                                 "joint (a gripper's fingers) is locked at zero, its bodies carried as fixed mass")
    p.add_argument("--base", help="a URDF arm's base link (default the root link)")
    p.add_argument("--payload", help="a point mass at the tip frame, e.g. '2 kg' (with --tip)")
    p.add_argument("--payload-range", metavar="LOW:HIGH",
                   help="payloads (kg) to check the design and its payload dial at, e.g. '0:5' or '0 kg:5 kg' "
                        "(with --tip; a URDF arm, designed on the general model; default 0 to the payload + 1 kg)")
    p.add_argument("--reach", help="how far beyond a URDF arm's links a spring end may sit, e.g. '5 cm': beyond "
                                   "each link's geometry (its collision shapes' bounding box; default 3 cm, '0' for "
                                   "none), or beyond the link's joints where the file gives no geometry (default 15 %% "
                                   "of the arm's length); designs a URDF arm on the general model")
    p.add_argument("--package-dir", action="append", default=[], metavar="DIR",
                   help="a folder that holds the packages a URDF's package:// meshes name (repeatable; also "
                        "searched: folders above the URDF, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH)")
    p.add_argument("--workspace", help="a URDF arm's joint ranges to hold, in degrees within its limits, e.g. "
                                       "'shoulder_lift_joint=-180:0,elbow_joint=-150:150' (designs it on the general "
                                       "model)")
    p.add_argument("--mjcf", metavar="FILE.xml",
                   help="also write the arm and its springs as a MuJoCo model (MJCF): the bodies, inertias and "
                        "joints (named as in the URDF), each spring a spatial tendon between two sites; for a "
                        "URDF arm the realised springs go beside it in FILE.realised.xml")
    p.add_argument("--allow-large", action="store_true", help="allow arms of more than 8 links")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--debug", action="store_true", help="show the traceback of an unexpected error")
    args = parser.parse_args(argv)
    try:
        status = _design(args)
        print(f"\ndone in {time.perf_counter() - started:.1f} s (wall time of the whole command)")
        return status
    except SpringlabError as err:
        print(f"springlab: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("springlab: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the output piped into a reader that stopped (`| head`): no defect, nothing to say
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # Python's exit flush must not fail again
        return 141  # 128 + SIGPIPE, as a shell tool's
    except Exception as err:  # a defect in springlab: one line, the traceback on request
        if args.debug:
            raise
        print(f"springlab: internal error ({type(err).__name__}: {err}); rerun with --debug and report it",
              file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":
    sys.exit(main())
