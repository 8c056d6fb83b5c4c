"""Cross-entropy method on steplearn/Footstep-v0 under experiment C's pushes.

Run from the repository root after `pip install ./python` (and `pip install gymnasium`):

    python python/examples/cem.py --quick        # about 6 minutes on two cores (5 min 48 s measured)
    python python/examples/cem.py                # larger population, more seeds and footsteps

A linear policy on the sagittal observation, dF = w . (theta_E, theta_E_dot, F_R, F_E) + b
(clipped to the action bounds), is trained with the cross-entropy method (numpy only): each
generation samples a population from a diagonal Gaussian over (w, b), scores every candidate
by its mean return over the same training seeds (common random numbers: the same pushes for
every candidate), and refits the Gaussian to the elite. The final mean policy is then compared
on held-out seeds, the same pushes for each, with

- the model: zero actions, the Capture Step controller alone (the pendulum-cart learner before
  it has learned anything, and what `run_trial` walks as the model on the same pushes);
- eq. (6) at footstep level: a `steplearn.Lwpr` on (theta_E, theta_E_dot, F_R), queried once
  per footstep and trained at each touch-down towards its prediction plus eta G (G = the
  pendulum-cart error of the step, `info["g"]`). This is NOT the Rust learner of the
  experiments (which queries every control tick and has a gain guard, prior, trust region and
  anti-windup): the environment holds one action per footstep and cannot host that learner.

That learner itself is compared on the same pushes through the Rust bench: experiment C on the
held-out seeds (LWPR + pendulum-cart), counting the pushes each walker absorbs of the first K
before its first fall (`--compare-pushes K`, 0 to skip).

Episodes run in threads, one environment each: `step` releases the GIL.
"""

from __future__ import annotations

import argparse
import csv
import os
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Callable, List, Optional, Tuple

import numpy as np

import steplearn
import steplearn.gym

Policy = Callable[[np.ndarray], float]


def episode(env: steplearn.gym.FootstepEnv, seed: int, policy, learner=None) -> Tuple[float, bool, int]:
    """(return, fell, footsteps) of one episode; `learner(obs, action, next_info)` may learn."""
    obs, _ = env.reset(seed=seed)
    lo, hi = env.action_space.low[0], env.action_space.high[0]
    total, steps = 0.0, 0
    while True:
        a = float(np.clip(policy(obs), lo, hi))
        nxt, r, terminated, truncated, info = env.step(np.array([a]))
        if learner is not None:
            learner(obs, a, info)
        total += r
        steps += 1
        obs = nxt
        if terminated or truncated:
            return total, terminated, steps


def pushes_absorbed(env: steplearn.gym.FootstepEnv, seed: int, policy: Policy, k: int) -> int:
    """How many of the first `k` pushes of `seed` the policy absorbs before its first fall."""
    obs, _ = env.reset(seed=seed)
    lo, hi = env.action_space.low[0], env.action_space.high[0]
    while True:
        obs, _, terminated, truncated, info = env.step(np.array([float(np.clip(policy(obs), lo, hi))]))
        delivered = info["pushes_delivered"]
        if terminated:
            return min(max(delivered - 1, 0), k)
        if delivered > k:
            return k
        if truncated:
            raise RuntimeError(f"seed {seed}: {k} pushes need more than max_footsteps footsteps")


def paper_learner(seeds: List[int], k: int, out: str) -> dict:
    """Experiment C through the Rust bench, LWPR + pendulum-cart (the paper's learner, queried
    every control tick and trained at every touch-down): per seed, the pushes of the first `k`
    the learned walker and the model absorb before their first fall (its `pushes.csv`)."""
    bench = (steplearn.Bench(steplearn.Registry.builtin()).approximators(["lwpr"])
             .rules(["pendulum-cart"]).experiments(["stability"])
             .first_seed(seeds[0]).seeds(len(seeds)).out(out))
    bench.run()
    result = {}
    for s in seeds:
        fell = {"model": [], "learned": []}
        with open(os.path.join(out, f"stability__lwpr__pendulum-cart__s{s}", "pushes.csv")) as f:
            for row in csv.DictReader(f):
                if row["controller"] in fell:
                    fell[row["controller"]].append(row["fell"] == "true")
        result[s] = {c: next((i for i, x in enumerate(v[:k]) if x), min(k, len(v)))
                     for c, v in fell.items()}
    return result


def linear(theta: np.ndarray) -> Policy:
    w, b = theta[:4], theta[4]
    return lambda obs: float(w @ obs[:4] + b)


class FootstepLwpr:
    """Eq. (6) at footstep level with steplearn.Lwpr: dF = F(x); at touch-down, F(x) <- F(x) + eta G."""

    def __init__(self, eta: float) -> None:
        self.eta = eta
        self.model = steplearn.Lwpr(3, 1, init_d=25.0, init_alpha=100.0, w_gen=0.2)

    def policy(self, obs: np.ndarray) -> float:
        return float(self.model.predict(obs[:3])[0])

    def learn(self, obs: np.ndarray, action: float, info: dict) -> None:
        if info["g"]:
            self.model.update(obs[:3], [action + self.eta * info["g"][0]])


def main(argv: Optional[List[str]] = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="small run, about 6 minutes on two cores")
    p.add_argument("--generations", type=int, default=8)
    p.add_argument("--population", type=int, default=16)
    p.add_argument("--elite", type=float, default=0.25, help="elite share")
    p.add_argument("--train-seeds", type=int, default=3)
    p.add_argument("--test-seeds", type=int, default=5)
    p.add_argument("--max-footsteps", type=int, default=60)
    p.add_argument("--eta", type=float, default=0.2, help="eq. (6) rate of the footstep LWPR (m/rad)")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--compare-pushes", type=int, default=10,
                   help="compare pushes absorbed of the first K with experiment C's learner (0: skip)")
    p.add_argument("--seed", type=int, default=0, help="the CEM's own sampling seed")
    args = p.parse_args(argv)
    if args.quick:
        args.generations, args.population, args.train_seeds = 3, 8, 2
        args.test_seeds, args.max_footsteps = 3, 30
    t0 = time.perf_counter()
    envs = [steplearn.gym.FootstepEnv(pushes="experiment-c", max_footsteps=args.max_footsteps)
            for _ in range(args.workers)]
    train = list(range(100, 100 + args.train_seeds))  # training pushes
    test = list(range(args.test_seeds))  # held-out pushes (experiment C's seeds 0, 1, ...)
    pool = ThreadPoolExecutor(args.workers)

    def score_all(thetas: List[np.ndarray]) -> np.ndarray:
        chunks = [thetas[i::args.workers] for i in range(args.workers)]

        def run(i: int) -> List[float]:
            return [np.mean([episode(envs[i], s, linear(t))[0] for s in train]) for t in chunks[i]]

        scores = list(pool.map(run, range(args.workers)))
        out = np.empty(len(thetas))
        for i, sc in enumerate(scores):
            out[i::args.workers] = sc
        return out

    rng = np.random.default_rng(args.seed)
    mean = np.zeros(5)
    std = np.array([1.0, 0.1, 0.5, 1.0, 0.02])  # theta_E (rad), rate (rad/s), F_R, F_E (m), b (m)
    n_elite = max(2, int(round(args.elite * args.population)))
    for g in range(args.generations):
        thetas = [mean + std * rng.standard_normal(5) for _ in range(args.population)]
        scores = score_all(thetas)
        elite = np.array([thetas[i] for i in np.argsort(scores)[-n_elite:]])
        mean, std = elite.mean(axis=0), elite.std(axis=0) + 1e-3
        print(f"generation {g}: best {scores.max():9.3f}  mean {scores.mean():9.3f}  "
              f"w = {np.array2string(mean, precision=3)}", flush=True)

    print(f"\nheld-out seeds {test}, experiment C pushes, max_footsteps {args.max_footsteps}")
    print(f"{'policy':<22}" + "".join(f"  {'seed ' + str(s) + ': return (fell) steps':<25}"
                                      for s in test))
    rows = []
    env = envs[0]
    for name, make_policy in [
        ("model (zero actions)", lambda: (lambda obs: 0.0, None)),
        ("CEM linear", lambda: (linear(mean), None)),
        ("footstep LWPR eq.(6)", lambda: (lambda l: (l.policy, l.learn))(FootstepLwpr(args.eta))),
    ]:
        results = []
        for s in test:
            policy, learn = make_policy()  # a fresh learner per seed
            results.append(episode(env, s, policy, learn))
        rows.append((name, results))
        cells = "".join(f"  {r:9.3f} ({int(f)}) {n:3d} steps" for r, f, n in results)
        print(f"{name:<22}{cells}")
    print()
    for name, results in rows:
        rets = [r for r, _, _ in results]
        print(f"{name:<22} mean return {np.mean(rets):9.3f}, falls {sum(f for _, f, _ in results)}"
              f"/{len(results)}, footsteps {sum(n for _, _, n in results)}")
    # The same pushes, counted as pushes absorbed before the first fall: the CEM policy, the
    # model in the environment, and experiment C's learned walker and model (the Rust learner).
    k = args.compare_pushes
    if k > 0:
        long_env = steplearn.gym.FootstepEnv(pushes="experiment-c", max_footsteps=40 * k)
        cem = [pushes_absorbed(long_env, s, linear(mean), k) for s in test]
        zero = [pushes_absorbed(long_env, s, lambda obs: 0.0, k) for s in test]
        with tempfile.TemporaryDirectory() as out:
            c = paper_learner(test, k, out)
        print(f"\npushes absorbed of the first {k} before the first fall, seeds {test}:")
        print(f"{'CEM linear (environment)':<34} {cem}  mean {np.mean(cem):.1f}")
        print(f"{'model (environment, zero actions)':<34} {zero}  mean {np.mean(zero):.1f}")
        model = [c[s]['model'] for s in test]
        learned = [c[s]['learned'] for s in test]
        print(f"{'model (experiment C)':<34} {model}  mean {np.mean(model):.1f}")
        print(f"{'LWPR + pendulum-cart (experiment C)':<34} {learned}  mean {np.mean(learned):.1f}")
    print(f"\ntotal {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
