"""Command-line entry: `python -m export <command>`. Thin: each command calls one module."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .contract import ContractError
from .sample.request import PredictError

# Errors a user can cause and fix; they get one readable line, never a traceback.
USER_ERRORS = (ContractError, PredictError, FileNotFoundError, ValueError, RuntimeError)


def _source(args):
    from .data.sources import default_source, source_for
    return source_for(args.data) if getattr(args, "data", None) else default_source()


def _data(args) -> None:
    from .data.build import build
    from .paths import CLIPS_DIR, RUNS_DIR
    # The site's clips are replaced only by the default data or when asked: a user's folder converts
    # into runs/data/<folder>/ unless --out names another place.
    out = Path(args.out) if args.out else (RUNS_DIR / "data" / Path(args.data).name if args.data else CLIPS_DIR)
    index = build(_source(args), out, replace=args.replace)
    print(f"clips in {out}")
    roles: dict[str, int] = {}
    for c in index["clips"]:
        roles[c["role"]] = roles.get(c["role"], 0) + 1
    print(f"wrote {len(index['clips'])} clips ({', '.join(f'{n} {r}' for r, n in sorted(roles.items()))}), "
          f"data {index['data_hash'][:19]}")


def _train(args) -> None:
    import torch

    from .config import load_config
    from .paths import RUNS_DIR
    from .pipeline import train
    from .train.loop import world
    cfg = load_config(args.config)
    run_dir = Path(args.run_dir) if args.run_dir else RUNS_DIR / cfg["id"]
    _, model = train(cfg, _source(args).clips(), run_dir, resume=args.resume, steps=args.steps,
                     batch_size=args.batch_size)
    rank, size = world()
    name = "weights.pt" if size == 1 else f"weights-rank{rank}.pt"
    run_dir.mkdir(parents=True, exist_ok=True)
    torch.save(model.state_dict(), run_dir / name)
    if rank == 0:
        print(f"trained {cfg['id']}: {run_dir / name}")


def _models(args) -> None:
    from .config import load_config
    from .paths import CONFIGS_DIR
    from .pipeline import build_models
    site = json.loads((CONFIGS_DIR / "site.json").read_text())["models"]
    configs = [(name, load_config(name)) for name in site]
    unknown = set(args.only or []) - {c["id"] for _, c in configs}
    if unknown:
        raise ValueError(f"--only names unknown models {sorted(unknown)}")
    doc = build_models(configs, _source(args) if args.data else None, only=args.only, resume=args.resume)
    print(f"wrote {len(doc['models'])} models to public/models/manifest.json")


def _predict(args) -> None:
    from .data.clip_json import read_clip
    from .paths import CLIPS_DIR, MODELS_DIR
    from .sample.predictor import load_predictor
    from .sample.request import Request
    predictor = load_predictor(args.model, Path(args.models_dir) if args.models_dir else MODELS_DIR)
    clip = read_clip(CLIPS_DIR / f"{args.clip}.json")
    n = predictor.params["history_frames"]
    if not 0 <= args.start <= len(clip) - n:
        raise PredictError(f"start frame {args.start} leaves fewer than {n} history frames in {args.clip} "
                           f"({len(clip)} frames)")
    history = clip.positions[args.start:args.start + n]
    req = Request(k=args.k, seed=args.seed, actions=[a for a in (args.actions or "").split(",") if a],
                  horizon_frames=args.horizon, controls=json.loads(args.controls) if args.controls else {})
    pred = predictor.predict(history, req)
    doc = {"model": args.model, "clip": args.clip, "start": args.start, "request": req.to_json(), **pred.to_json()}
    text = json.dumps(doc)
    if args.out:
        Path(args.out).write_text(text)
        print(f"wrote {args.out}: K={pred.futures.shape[0]}, lengths {pred.lengths.tolist()}")
    else:
        print(text)


def _vectors(args) -> None:
    from .vectors import write_all
    print("wrote vectors:", ", ".join(write_all()))


def _evaluate(args, extra: dict | None = None) -> None:
    from .data.sources import default_source
    from .eval.harness import evaluate, load_eval_config
    from .eval.card import write_card
    from .eval.report import write_json, write_markdown
    from .paths import MODELS_DIR
    doc = evaluate(default_source().clips(), load_eval_config(args.config),
                   models_dir=Path(args.models_dir) if args.models_dir else MODELS_DIR)
    doc.update(extra or {})
    write_json(doc)
    write_markdown(doc)
    write_card(doc)
    print(f"wrote public/results.json, docs/RESULTS.md and docs/MODEL_CARD.md in {doc['seconds']:.0f} s")


def _results(args) -> None:
    import time

    from .data.sources import default_source
    from .eval.harness import load_eval_config
    from .eval.seeds import train_seeds
    cfg = load_eval_config(args.config)
    start = time.time()
    for note in train_seeds(default_source().clips(), list(cfg["training_seeds"])):
        print(note)
    # Training the extra seeds is reported apart from the evaluation's own time (seeds already in runs/ are kept).
    seconds = round(time.time() - start, 1)
    print(f"extra seeds and ablations ready in {seconds:.0f} s")
    _evaluate(args, {"seed_training_seconds": seconds})


def _bench(args) -> None:
    from .bench import bench, native_only
    from .bench.report import table
    from .paths import MODELS_DIR
    models_dir = Path(args.models_dir) if args.models_dir else MODELS_DIR
    if args.native_only:
        doc = native_only(models_dir, runs=args.runs, warmup=args.warmup)
        print(json.dumps(doc))
        return
    doc = bench(models_dir, runs=args.runs, warmup=args.warmup)
    rows = [[t["target"], t["limit"], {True: "met", False: "MISSED", None: "not measured"}[t["met"]]] for t in doc["targets"]]
    print(table(["target", "limit", "result"], rows))
    print(f"wrote {doc['json_path']} and docs/PERFORMANCE.md in {doc['seconds']:.0f} s")


def _strips(args) -> None:
    from .strips import OUT_DIR, run
    run(args.model or None, Path(args.out) if args.out else OUT_DIR)


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m export", description="motion-futures: data, training, export")
    sub = p.add_subparsers(dest="command", required=True)

    c = sub.add_parser("data", help="convert motion data into clips with the train/test split")
    c.add_argument("--data", help="a folder of motion files (default: data/cmu and the DeepMimic clips in pybullet)")
    c.add_argument("--out", help="output folder (default: public/clips for the default data, "
                                 "runs/data/<folder> for --data)")
    c.add_argument("--replace", action="store_true",
                   help="replace clips in --out that another source wrote (otherwise that is refused)")
    c.set_defaults(run=_data)

    c = sub.add_parser("train", help="train one config (also under torchrun --nproc_per_node N)")
    c.add_argument("--config", required=True, help="a file in configs/, e.g. regression.json")
    c.add_argument("--data", help="a folder of motion files (default: data/cmu and the DeepMimic clips)")
    c.add_argument("--run-dir", help="checkpoints and weights (default: runs/<model id>)")
    c.add_argument("--steps", type=int, help="override the config's training steps")
    c.add_argument("--batch-size", type=int, help="override the config's global batch size")
    c.add_argument("--resume", action="store_true", help="continue from the run's checkpoint")
    c.set_defaults(run=_train)

    c = sub.add_parser("models", help="convert the data, train and export every served model into public/")
    c.add_argument("--data", help="a folder of motion files (default: the DeepMimic clips)")
    c.add_argument("--only", nargs="*", help="model ids to rebuild (default: all in configs/site.json)")
    c.add_argument("--resume", action="store_true",
                   help="continue each model's checkpoint in runs/<id>/ (e.g. trained side by side with "
                        "`train`); a finished one is only exported")
    c.set_defaults(run=_models)

    c = sub.add_parser("predict", help="predict futures for a clip window with the served models")
    c.add_argument("--model", required=True)
    c.add_argument("--clip", required=True)
    c.add_argument("--start", type=int, default=0, help="first history frame")
    c.add_argument("--k", type=int, default=1)
    c.add_argument("--seed", type=int, default=0)
    c.add_argument("--actions", help="comma-separated action sequence")
    c.add_argument("--horizon", type=int, help="frames to predict (default: one graph call)")
    c.add_argument("--controls", help='JSON object of model controls, e.g. \'{"sigma_scale": 1.5}\'')
    c.add_argument("--models-dir", help="default: public/models")
    c.add_argument("--out", help="write the prediction JSON here instead of printing it")
    c.set_defaults(run=_predict)

    c = sub.add_parser("vectors", help="write the shared Python -> TypeScript test vectors")
    c.set_defaults(run=_vectors)

    c = sub.add_parser("bench", help="browser and native timings: bench/results.json and docs/PERFORMANCE.md")
    c.add_argument("--runs", type=int, default=20, help="timed predictions per case, after the warm-up")
    c.add_argument("--warmup", type=int, default=5)
    c.add_argument("--models-dir", help="default: public/models")
    c.add_argument("--native-only", action="store_true", help="only the native timings, as JSON to stdout")
    c.set_defaults(run=_bench)

    c = sub.add_parser("strips", help="look at the motion: held-out futures at 0-3 s as pictures in docs/strips/")
    c.add_argument("--model", action="append", help="a served model id (repeatable; default: every learned one)")
    c.add_argument("--out", help="default: docs/strips")
    c.set_defaults(run=_strips)

    for name, run, text in (("evaluate", _evaluate, "evaluate every results row on held-out people: public/results.json, "
                                                    "docs/RESULTS.md, docs/MODEL_CARD.md"),
                            ("results", _results, "train the extra seeds and ablations into runs/seeds, then evaluate")):
        c = sub.add_parser(name, help=text)
        c.add_argument("--config", help="evaluation config (default: configs/eval.json)")
        c.add_argument("--models-dir", help="served models (default: public/models)")
        c.set_defaults(run=run)
    return p


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        args.run(args)
    except USER_ERRORS as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 0
