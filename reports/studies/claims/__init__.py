"""The source article's results as claims, each judged from the suite's own results
(``contact-vv article``): :data:`CLAIMS` lists them in the article's words with the
figures they come from and the function that judges each (:mod:`.static`, :mod:`.pin`,
:mod:`.fretting`); :func:`judge` turns the results at hand into one
:class:`~reports.studies.claims.finding.Finding` per claim."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from reports.registry.errors import IncompleteRun
from reports.store.readers import DamagedResult
from reports.studies.claims import fretting, pin, static
from reports.studies.claims.finding import Article, Finding, MissingSource, undecided


@dataclass(frozen=True)
class Claim:
    number: int
    text: str
    figure: str
    judge: Callable[[Article], Finding]


CLAIMS = (
    Claim(1, "Hertz, frictionless: σ_VM,max / p0 = 0.620 at z / a0 = 0.48", "8a",
          static.hertz_peak),
    Claim(2, "worn pin, isotropic: w_max(s), a(s), p_max(s) follow Argatov's asymptotic "
          "solution and Hegadekatte's cap model", "6, 7", pin.worn_pin),
    Claim(3, "frictionless worn pin: σ_VM,max decreases with s and moves deeper "
          "(z / a0 > 0.48), staying on the axis", "8a, 9", pin.frictionless_depth),
    Claim(4, "with friction the maximum stays below the surface while running in and moves "
          "to the surface at some sliding distance; above μ ≈ 0.35 it is on the surface "
          "throughout", "9", static.surface_threshold),
    Claim(5, "as μ grows, σ_VM,max grows, moves away from the centre and becomes shallower",
          "19", static.friction_trend),
    Claim(6, "orthotropic pin (μ1 = 0.25, μ2 = 0.5, i2 = 2 i1): the wear grows with β, but "
          "W(90°) − W(0°) is not twice W(45°) − W(0°)", "10", pin.wear_with_beta),
    Claim(7, "orthotropic pin: p_max and contact area differ markedly for β = 0, 45, 90°",
          "11", pin.pressure_and_area),
    Claim(8, "orthotropic pin at fixed s: σ_VM,max grows with β and moves towards the "
          "surface", "12", pin.stress_with_beta),
    Claim(9, "β = 45°: the tangential traction is not parallel to the slip, and the "
          "yz-plane stresses lose their symmetry", "13, 20", pin.oblique_traction),
    Claim(10, "fretting (μ1 = 0.1, μ2 = 0.65): β = 0 gross slip, the wear widens the contact; "
          "β = 90 partial slip with a crown-shaped wear around an unworn stick zone",
          "15, 16", fretting.under_readings(fretting.regimes, note=fretting.AXES_NOTE)),
    Claim(11, "fretting, gross slip (β = 30): the pressure falls while the contact grows",
          "17a", fretting.under_readings(fretting.gross_slip_pressure, fretting.READINGS)),
    Claim(12, "fretting, partial slip (β = 90): the pressure turns towards a nearly uniform "
          "distribution over the stick zone, with a maximum more than twice the first "
          "cycles'", "17b",
          fretting.under_readings(fretting.partial_slip_pressure, note=fretting.AXES_NOTE)),
    Claim(13, "the regime turns from gross to partial slip at β ≈ 67°, where σ_VM,max at "
          "10⁵ cycles is largest", "18", fretting.regime_change),
)


def numbers(text: str | None) -> tuple[int, ...]:
    """``--claims 1-5,9``: the claims' numbers (every claim for None); UserError on one
    that is not a claim."""
    from reports.registry.errors import UserError

    known = tuple(c.number for c in CLAIMS)
    if text is None:
        return known
    out: list[int] = []
    for token in (t.strip() for t in text.split(",") if t.strip()):
        lo, dash, hi = token.partition("-")
        try:
            span = range(int(lo), int(hi) + 1) if dash else [int(lo)]
        except ValueError:
            raise UserError(f"--claims {text!r}: {token!r} is not N or N-M") from None
        # the ends first: a range is never expanded beyond the claims (1-999999999999)
        if not span or span[0] < min(known) or span[-1] > max(known) or \
                any(n not in known for n in span):
            raise UserError(f"--claims {text!r}: the claims are numbered 1 to {len(known)}")
        out += [n for n in span if n not in out]
    if not out:
        raise UserError(f"--claims {text!r}: no claim named")
    return tuple(sorted(out))


def judge(article: Article, claims: tuple[int, ...]) -> dict[int, Finding]:
    """One finding per claim named; a claim whose results are missing or unreadable
    cannot be decided, and says why."""
    out = {}
    for claim in (c for c in CLAIMS if c.number in claims):
        try:
            out[claim.number] = claim.judge(article)
        except (MissingSource, DamagedResult, IncompleteRun) as exc:
            out[claim.number] = undecided(str(exc))
    return out
