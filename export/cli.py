"""Command-line entry: `python -m export <command>`; each command lives in its own module."""
from __future__ import annotations

import argparse
import sys

from .contract import ContractError

# Errors a user can cause and fix; they get one readable line, never a traceback.
USER_ERRORS = (ContractError, FileNotFoundError, ValueError, RuntimeError)


def _data(args) -> None:
    from .data.build import build
    from .data.sources import default_source, source_for
    source = source_for(args.data) if args.data else default_source()
    index = build(source, args.out) if args.out else build(source)
    roles = {}
    for c in index["clips"]:
        roles[c["role"]] = roles.get(c["role"], 0) + 1
    print(f"wrote {len(index['clips'])} clips ({', '.join(f'{n} {r}' for r, n in sorted(roles.items()))}), "
          f"data {index['data_hash'][:19]}")


def _vectors(args) -> None:
    from .vectors import write_all
    print("wrote vectors:", ", ".join(write_all()))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m export", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("data", help="convert motion data into public/clips with the train/test split")
    p.add_argument("--data", help="a folder of BVH or npz files (default: the DeepMimic clips in pybullet)")
    p.add_argument("--out", help="output folder (default: public/clips)")
    p.set_defaults(run=_data)
    p = sub.add_parser("vectors", help="write the shared Python -> TypeScript test vectors")
    p.set_defaults(run=_vectors)
    args = parser.parse_args(argv)
    try:
        args.run(args)
    except USER_ERRORS as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 0
