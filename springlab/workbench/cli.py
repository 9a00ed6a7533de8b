"""The command line: ``springlab design my_arm.toml``.

Prints the ranked designs of :func:`springlab.design.rank.design_arm` as a table
and writes the chosen one (rank 1 unless ``--pick``) as JSON.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from springlab.errors import SpringlabError


def _design(args) -> int:
    from springlab.design.rank import design_arm
    from springlab.model.armfile import load_arm

    spec = load_arm(args.arm_file, allow_large=args.allow_large)
    report = design_arm(spec, method=args.method, max_designs=args.max_designs,
                        max_configurations=args.max_configurations, seed=args.seed, progress=not args.quiet)
    print(f"# {spec.name}: n = {spec.n} links (ground included), payload {spec.payload:g} kg")
    print(f"{report.configurations_tried} configurations tried in {report.seconds:.1f} s, "
          f"{len(report.designs)} verified designs, {len(report.rejected)} rejected\n")
    if not report.designs:
        print("no design found within the limits; relax max_stiffness or max_attachment", file=sys.stderr)
        return 1
    print(report.table())
    if not 1 <= args.pick <= len(report.designs):
        raise SpringlabError(f"--pick must be in 1..{len(report.designs)}, got {args.pick}")
    chosen = report.designs[args.pick - 1]
    out = Path(args.json or Path(args.arm_file).with_suffix(".design.json").name)
    out.write_text(json.dumps({"arm": spec.name, "source": str(args.arm_file), "rank": args.pick} | chosen.to_dict(),
                              indent=1) + "\n")
    print(f"\ndesign {args.pick} written to {out}")
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="springlab", description="Spring gravity balancing of robot arms.")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("design", help="rank verified spring designs for an arm file (.toml or .json)")
    p.add_argument("arm_file")
    p.add_argument("--json", help="where to write the chosen design (default: <arm>.design.json here)")
    p.add_argument("--pick", type=int, default=1, help="which ranked design to write (default 1)")
    p.add_argument("--method", default="no auxiliary links", choices=("no auxiliary links", "ground springs"),
                   help="paper 000's configurations (default), or n - 1 springs from the base column")
    p.add_argument("--max-designs", type=int, default=10)
    p.add_argument("--max-configurations", type=int, default=None)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--allow-large", action="store_true", help="allow arms of more than 8 links")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    try:
        return _design(args)
    except SpringlabError as err:
        print(f"springlab: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
