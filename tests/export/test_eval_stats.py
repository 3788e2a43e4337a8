"""The evaluation's statistics on synthetic rows: people as the unit of the bootstrap, the minimum support, the
practical minimum, trends tested as trends, Holm's correction, and unusable parts that keep the data's status."""
from types import SimpleNamespace

import numpy as np
import pytest

from export.eval import stats as S


def people_units(takes_per_person: list[int], items_per_take: int = 3) -> S.Units:
    """Items of takes of people: person p has takes_per_person[p] takes of items_per_take items each."""
    takes, people = [], []
    for p, n in enumerate(takes_per_person):
        for t in range(n):
            takes += [f"p{p}-t{t}"] * items_per_take
            people += [p] * items_per_take
    return S.units(takes, ["walk"] * len(takes), people)


def two_level(u: S.Units, rounds: int = 2000, seed: int = 0) -> np.ndarray:
    return S.bootstrap_weights(S.take_people(u), rounds, seed)


def clear_gap(u: S.Units, gap: float = 0.2, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Row a below row b by `gap` (metres) on every item, with a little item noise."""
    rng = np.random.default_rng(seed)
    b = 0.5 + rng.normal(0, 0.01, len(u))
    return b - gap + rng.normal(0, 0.01, len(u)), b


# --- the two-level bootstrap ---------------------------------------------------------------------

def test_take_people_maps_each_take_to_its_person():
    u = S.units(["b", "a", "c", "a"], ["x"] * 4, ["9", "9", "7", "9"])
    assert S.take_people(u).tolist() == [1, 1, 0]             # takes a, b of person 9 (index 1); c of person 7
    with pytest.raises(ValueError, match="more than one person"):
        S.take_people(S.units(["a", "a"], ["x", "x"], ["1", "2"]))


def test_a_resample_draws_people_then_their_own_takes():
    u = people_units([3, 1, 2])
    tp = S.take_people(u)
    w = two_level(u, rounds=500, seed=3)
    assert w.shape == (500, 6) and (w == np.round(w)).all()
    for p, n in enumerate([3, 1, 2]):
        # a person drawn c times gives c x (its takes) draws among its own takes
        drawn = w[:, tp == p].sum(1) / n
        assert (drawn == np.round(drawn)).all()
    assert (sum(w[:, tp == p].sum(1) / n for p, n in enumerate([3, 1, 2])) == 3).all()   # 3 people drawn
    # a person left out of a resample takes all its takes out with it
    assert any((w[:, tp == 0] == 0).all(1))
    assert S.bootstrap_weights(3, 10).sum(1).tolist() == [3.0] * 10   # an int: takes of distinct people


def test_the_two_level_bar_is_wider_when_one_person_dominates():
    """One person has 30 of 36 takes and the people differ: resampling takes alone treats the 30 as
    independent evidence; resampling people does not."""
    rng = np.random.default_rng(0)
    u = people_units([30, 2, 2, 2], items_per_take=4)
    person_effect = rng.normal(0, 0.05, 4)[S.take_people(u)[u.take]]
    a = 0.5 + person_effect + rng.normal(0, 0.01, len(u))
    b = np.full(len(u), 0.5)
    takes_only = S.bootstrap_weights(int(u.take.max()) + 1, 2000)
    wide = S.compare(a, b, u, two_level(u), 0.0, 0.0, "greater", unit="m")
    narrow = S.compare(a, b, u, takes_only, 0.0, 0.0, "greater", unit="m")
    assert wide["boot_std"] > 2 * narrow["boot_std"]
    assert wide["bar"] > narrow["bar"] and wide["difference"] == narrow["difference"]


def test_the_two_level_bar_is_close_to_the_take_bar_when_people_are_balanced():
    """Six people of four takes, no person effect: the two bootstraps agree up to the two-level bootstrap's
    known excess (variance x (2 - 1/P - 1/n) = 1.58 at most here, an sd ratio of about 1.26)."""
    rng = np.random.default_rng(1)
    u = people_units([4] * 6, items_per_take=4)
    take_effect = rng.normal(0, 0.05, int(u.take.max()) + 1)[u.take]
    a = 0.5 + take_effect + rng.normal(0, 0.01, len(u))
    b = np.full(len(u), 0.5)
    ratios = []
    for seed in range(4):
        two = S.compare(a, b, u, two_level(u, seed=seed), 0.0, 0.0, "greater", unit="m")["boot_std"]
        one = S.compare(a, b, u, S.bootstrap_weights(24, 2000, seed), 0.0, 0.0, "greater", unit="m")["boot_std"]
        ratios.append(two / one)
    assert 0.9 < np.mean(ratios) < 1.4


# --- minimum support ------------------------------------------------------------------------------

def test_one_person_or_two_people_with_seven_takes_are_insufficient_data():
    assert (S.MIN_PEOPLE, S.MIN_TAKES) == (3, 8)
    one = people_units([10])
    a, b = clear_gap(one)
    c = S.compare(a, b, one, two_level(one), 0.0, 0.0, "less", unit="m")
    assert c["status"] == S.INSUFFICIENT and (c["people"], c["takes"]) == (1, 10)
    assert "1 people and 10 takes" in c["reason"]
    few = people_units([4, 3])
    a, b = clear_gap(few)
    c = S.compare(a, b, few, two_level(few), 0.0, 0.0, "less", unit="m")
    assert c["status"] == S.INSUFFICIENT and (c["people"], c["takes"]) == (2, 7)
    assert "2 people and 7 takes" in c["reason"] and "at least 3 people and 8 takes" in c["reason"]
    # the same gap on 3 people and 8 takes holds
    enough = people_units([3, 3, 2])
    a, b = clear_gap(enough)
    assert S.compare(a, b, enough, two_level(enough), 0.0, 0.0, "less", unit="m")["status"] == S.HOLDS


def test_support_counts_only_the_items_both_rows_have():
    u = people_units([3, 3, 3])
    a, b = clear_gap(u)
    a[u.person == "2"] = np.nan                                  # row a never predicts person 2
    c = S.compare(a, b, u, two_level(u), 0.0, 0.0, "less", unit="m")
    assert (c["people"], c["takes"]) == (2, 6) and c["status"] == S.INSUFFICIENT


# --- identity and the practical minimum -----------------------------------------------------------

def test_identical_rows_are_no_difference_whatever_the_bar():
    u = people_units([3, 3, 3])
    a, _ = clear_gap(u)
    c = S.compare(a, a.copy(), u, two_level(u), 0.0, 0.0, "less", unit="m")
    assert c["status"] == S.NO_DIFFERENCE and c["difference"] == 0.0 and c["reason"] == "identical predictions"
    # float noise between two code paths that hold the same pose: the audit's -4.0e-09 m against 2σ 2.3e-09,
    # which the bar alone calls a win
    noisy = a - 4.0e-9 + np.random.default_rng(0).normal(0, 1e-10, len(u))
    c = S.compare(noisy, a, u, two_level(u), 0.0, 0.0, "less", unit="m")
    assert S.decide(c["difference"], c["bar"], "less") == S.HOLDS
    assert c["status"] == S.NO_DIFFERENCE
    # identity wins over support: one person, identical rows
    one = people_units([2])
    assert S.compare(a[:6], a[:6], one, two_level(one), 0, 0, "less")["status"] == S.NO_DIFFERENCE


def test_the_practical_minimum_by_unit():
    assert S.practical_minimum("m", 0.05) == 0.001                 # 1 mm beats 1% of 5 cm
    assert S.practical_minimum("m", 0.7) == pytest.approx(0.007)   # 1% of 0.7 m beats 1 mm
    assert S.practical_minimum("%", 40.0) == 1.0
    assert S.practical_minimum("mm", 180.0) == pytest.approx(1.8)
    assert S.practical_minimum("", 250.0) == pytest.approx(2.5)


def test_a_difference_below_the_practical_minimum_is_no_difference_never_holds_or_fails():
    u = people_units([3, 3, 3])
    b = np.full(len(u), 0.05)
    s = 1e-4                                                    # seed stds: a 2σ bar of 0.28 mm
    for gap in (0.0008, -0.0008):                               # below 1 mm, either way, beyond the bar
        c = S.compare(b - gap, b, u, two_level(u), s, s, "less", unit="m")
        assert c["bar"] < abs(gap) and c["status"] == S.NO_DIFFERENCE and "practical minimum" in c["reason"]
        assert S.decide(c["difference"], c["bar"], "less") == (S.HOLDS if gap > 0 else S.FAILS)
    c = S.compare(b - 0.0015, b, u, two_level(u), s, s, "less", unit="m")
    assert c["status"] == S.HOLDS                                # above 1 mm: the bar decides
    acc = np.full(len(u), 40.0)
    assert S.compare(acc + 0.8, acc, u, two_level(u), 0.1, 0.1, "greater", unit="%")["status"] == S.NO_DIFFERENCE
    assert S.compare(acc + 1.5, acc, u, two_level(u), 0.1, 0.1, "greater", unit="%")["status"] == S.HOLDS
    # a 'similar or better' part keeps its margin as its tolerance
    assert S.compare(acc, acc, u, two_level(u), 0.1, 0.1, "not_less", margin=5.0, unit="%")["status"] == S.HOLDS


# --- trends ---------------------------------------------------------------------------------------

SETTINGS = 4


def rising(u: S.Units, step: float, base: float = 30.0) -> list[np.ndarray]:
    """Four settings whose values rise by `step` each, the same item pattern in each."""
    pattern = base + np.random.default_rng(2).normal(0, 3.0, len(u))
    return [pattern + k * step for k in range(SETTINGS)]


def test_a_monotone_trend_against_the_claim_fails_where_consecutive_pairs_are_inconclusive():
    """Each step is 1.5 sigma of its pair (inconclusive), but the trend over the four settings is 4.7 sigma:
    a claim that the metric falls fails. (The audit's MOAC 23 -> 35 -> 40 -> 43.)"""
    u = people_units([3, 3, 3])
    w = two_level(u)
    s = 2.0                                                     # each row's seed std (points)
    step = 1.5 * np.sqrt(2) * s
    series = rising(u, step)
    for lo, hi in zip(series, series[1:]):
        assert S.compare(hi, lo, u, w, s, s, "less", unit="%")["status"] == S.INCONCLUSIVE
    t = S.trend(series, u, w, [s] * SETTINGS, "less", unit="%")
    assert t["status"] == S.FAILS
    assert t["slope"] == pytest.approx(step) and t["difference"] == pytest.approx(3 * step)
    assert t["bar"] == pytest.approx(2 * np.sqrt(1.8) * s, rel=1e-6)   # coefficients (-0.9, -0.3, 0.3, 0.9)
    assert t["values"] == pytest.approx([float(x.mean()) for x in series])


def test_a_trend_in_the_claimed_direction_holds_and_a_flat_one_is_no_difference():
    u = people_units([3, 3, 3])
    w = two_level(u)
    series = rising(u, 1.5 * np.sqrt(2) * 2.0)
    t = S.trend(series, u, w, [2.0] * SETTINGS, "greater", unit="%")
    assert t["status"] == S.HOLDS and t["p"] < 0.001
    flat = rising(u, 0.1)                                       # 0.3 points over the range, below 1 point
    assert S.trend(flat, u, w, [0.0] * SETTINGS, "greater", unit="%")["status"] == S.NO_DIFFERENCE
    same = [series[0]] * SETTINGS
    assert S.trend(same, u, w, [2.0] * SETTINGS, "greater", unit="%")["reason"] == "identical predictions"
    few = people_units([4, 3])
    assert S.trend(rising(few, 5.0), few, two_level(few), [0.0] * SETTINGS, "greater",
                   unit="%")["status"] == S.INSUFFICIENT
    with pytest.raises(ValueError, match="rises"):
        S.trend(series, u, w, [0.0] * SETTINGS, "not_less")


def test_a_trend_of_two_settings_is_the_pair():
    u = people_units([3, 3, 3])
    w = two_level(u)
    a, b = clear_gap(u, gap=0.01)
    pair = S.compare(b, a, u, w, 0.002, 0.003, "greater", unit="m")
    t = S.trend([a, b], u, w, [0.003, 0.002], "greater", unit="m")
    assert t["difference"] == pytest.approx(pair["difference"]) and t["bar"] == pytest.approx(pair["bar"])


def test_the_temperature_claims_are_trends_over_the_rows_settings():
    from export.eval.rows import CLAIMS, KP_TEMPERATURES, LONG, Trend
    trends = {c.id: c.parts[0] for c in CLAIMS if c.id.startswith("kp-") and c.id.endswith("-temperature")}
    assert set(trends) == {"kp-diversity-temperature", "kp-mpjpe-temperature", "kp-moac-temperature"}
    for t in trends.values():
        assert isinstance(t, Trend) and t.table == LONG and t.settings() == list(KP_TEMPERATURES)
    assert trends["kp-moac-temperature"].direction == "less"
    with pytest.raises(ValueError, match="increasing temperature"):
        Trend(LONG, ("keyposes-t0.5", "keyposes-t0.1"), "apd", "greater")


# --- p-values and Holm ----------------------------------------------------------------------------

def test_the_p_value_is_the_one_sided_normal_tail():
    assert S.p_value(2.0, 1.0, "greater") == pytest.approx(0.02275, abs=1e-5)
    assert S.p_value(2.0, 1.0, "less") == pytest.approx(0.97725, abs=1e-5)
    assert S.p_value(-1.0, 1.0, "not_less", margin=3.0) == pytest.approx(0.02275, abs=1e-5)
    assert S.p_value(5.0, 0.0, "greater") == 1.0


def test_holm_steps_down_by_hand():
    p = [0.030, 0.001, 0.040, 0.012, 0.20]
    # sorted: 0.001 x 5 = 0.005; 0.012 x 4 = 0.048; 0.030 x 3 = 0.090; 0.040 x 2 = 0.080 -> 0.090 (running max);
    # 0.20 x 1 -> 0.20
    assert S.holm(p) == pytest.approx([0.090, 0.005, 0.090, 0.048, 0.20])
    # step-down at 0.05: 0.001 <= 0.05/5, 0.012 <= 0.05/4 = 0.0125, 0.030 > 0.05/3: stop; 0.040 is not rejected
    # although 0.040 <= 0.05/2
    assert (S.holm(p) <= 0.05).tolist() == [False, True, False, True, False]
    assert S.holm([0.3, 0.2]) == pytest.approx([0.4, 0.4])          # 0.2 x 2 = 0.4, then max(0.4, 0.3)
    assert S.holm([0.9, 0.8]) == pytest.approx([1.0, 1.0])          # capped at 1
    assert S.holm([0.5]) == pytest.approx([0.5]) and len(S.holm([])) == 0


def test_holm_makes_a_part_beyond_its_bar_inconclusive_when_the_family_is_large():
    from export.eval.checks import holm_correct
    # 0.03 passes alone (and its 2σ bar), but is the second smallest of three: 0.03 x 2 = 0.06 > 0.05
    family = [{"status": S.HOLDS, "p": 0.03}, {"status": S.HOLDS, "p": 0.0001}, {"status": S.FAILS, "p": 0.99}]
    holm_correct(family, "claim parts")
    assert [x["status"] for x in family] == [S.INCONCLUSIVE, S.HOLDS, S.FAILS]
    assert family[0]["p_holm"] == pytest.approx(0.06) and "Holm's correction over 3 claim parts" in family[0]["reason"]


# --- combining, unusable parts and the report -----------------------------------------------------

def test_combine_ranks_no_difference_below_the_refusals():
    assert S.combine([S.HOLDS, S.NO_DIFFERENCE]) == S.NO_DIFFERENCE
    assert S.combine([S.INCONCLUSIVE, S.NO_DIFFERENCE]) == S.NO_DIFFERENCE
    assert S.combine([S.NO_DIFFERENCE, S.INSUFFICIENT]) == S.INSUFFICIENT
    assert S.combine([S.NO_DIFFERENCE, S.FAILS]) == S.FAILS


def synthetic_results(a: np.ndarray, b: np.ndarray, u: S.Units, table: str, ra: str, rb: str, metric: str):
    """by_table, store and tabs as checks.py reads them, for two rows of one table."""
    from export.eval.harness import RowStats
    rows = [{"id": r, "label": r, "kind": "model", "values": {metric: {"mean": float(v.mean()), "std": 1.0}}}
            for r, v in ((ra, a), (rb, b))]
    by_table = {table: {"id": table, "rows": rows, "truth": False, "in_sample": False}}
    store = {table: {ra: RowStats({metric: a}, {metric: 0.5}), rb: RowStats({metric: b}, {metric: 0.5})}}
    return by_table, store, {table: SimpleNamespace(units=u, weights=two_level(u))}


def test_an_unusable_part_keeps_what_the_data_would_say():
    """The padding claim (WAT Table 5): -3.2 points against a bar near 2.3, on a classifier that failed its check."""
    from export.eval.checks import comparisons, evaluate_claims
    from export.eval.report import part_text, status_text
    u = people_units([5, 5, 5, 4, 4, 4])
    rng = np.random.default_rng(4)
    b = 66.0 + rng.normal(0, 1.0, len(u))
    a = b - 3.2
    by_table, store, tabs = synthetic_results(a, b, u, "transitions", "wat-rnn", "wat-rnn-no-padding", "acc_pose")
    recognition = [{"table": "transitions", "metric": "acc_pose", "passed": False}]
    claims = {c["id"]: c for c in evaluate_claims(by_table, store, tabs, recognition)}
    part = claims["wat-padding"]["parts"][0]
    assert part["status"] == S.UNUSABLE and part["data_status"] == S.FAILS
    assert claims["wat-padding"]["status"] == S.UNUSABLE and claims["wat-padding"]["data_status"] == S.FAILS
    assert part_text(part).count("unusable; the data would say: fails") == 1
    assert status_text(claims["wat-padding"]) == "unusable; the data would say: fails"
    # the same numbers on a classifier that passed: the data's status stands
    ok = {c["id"]: c for c in evaluate_claims(by_table, store, tabs, [])}
    assert ok["wat-padding"]["status"] == S.FAILS and "data_status" not in ok["wat-padding"]
    # one counted claim part (every other claim's rows are missing)
    assert comparisons(list(claims.values()), [])["claims"] == 1


def test_copying_verdicts_say_no_different_for_no_difference():
    from export.eval.checks import copying_verdict
    c = {"baseline": "repeat-cycle-10", "baseline_label": "Repeat last cycle (10-frame history)"}
    assert copying_verdict({**c, "status": S.NO_DIFFERENCE}).startswith(
        "is no different from repeat last cycle (10-frame history)")
    assert copying_verdict({**c, "status": S.HOLDS}) == "beats repeat last cycle (10-frame history)"
    assert copying_verdict({**c, "status": S.INCONCLUSIVE}).startswith("does not beat")
