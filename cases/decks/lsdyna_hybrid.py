"""*AIRBAG_HYBRID (LS-DYNA Keyword User's Manual): a control volume of several ideal gases.

Cards after card 1: ATMOST ATMOSP ATMOSD GC CC HCONV (ambient temperature, pressure, density; heat convection);
C23 LCC23 A23 LCA23 CP23 LCP23 AP23 LCAP23 (vent and porosity orifices); OPT PVENT NGAS LCEFR LCIDM0 VNTOPT; then
per gas a card LCIDM LCIDT (unused) MW INITM A B C and a card FMASS. Gas i: molar mass MW, molar heat capacity
cp = A + B·T + C·T² (so cp per mass is (A + BT + CT²)/MW), initial mass fraction INITM in the bag. The inflow is
LCIDM0 split by the mass fractions FMASS (one inflator), or each gas's own LCIDM and LCIDT (one inflator each,
``inflator<i>`` when several gases are injected).
PVENT (gauge pressure at which venting starts) is the vent's pop pressure.
"""
from __future__ import annotations

from cases.decks.lsdyna_cards import W10, fields, refuse

__all__ = ["hybrid_gas"]


def _gases(deck, kw, cards, ngas):
    if len(cards) < 4 + 2 * ngas:
        raise kw.error(f"NGAS = {ngas} needs {2 * ngas} gas cards after card 4, got {len(cards) - 4}")
    out = []
    for i in range(ngas):
        c, f = cards[4 + 2 * i], cards[5 + 2 * i]
        lcidm, lcidt, _, mw, initm, a, b, cc = fields(kw, c, W10, "iiffffff")
        if not (mw and mw > 0):
            raise kw.error(f"gas {i + 1}: MW must be > 0", c[1])
        cp = [deck.si(x or 0.0, "molar_heat") for x in (a, b, cc)]
        while len(cp) > 1 and cp[-1] == 0.0:
            cp.pop()
        out.append(dict(lcidm=lcidm, lcidt=lcidt, M=deck.si(mw, "molar_mass"), initm=initm or 0.0, cp=cp,
                        fmass=fields(kw, f, W10, "f")[0] or 0.0, line=c[1]))
    return out


def _inflators(deck, kw, name, gases, names, lcidm0):
    def temperature(lcidt, stem):
        if not lcidt:
            raise kw.error("an injected gas needs a temperature curve LCIDT")
        t, v = deck.curve(kw, lcidt, "LCIDT", "time", "dimensionless")
        return deck.table_file(stem, t, v, "time [s],temperature [K]")

    def mass_flow(lcid, stem):
        t, m = deck.curve(kw, lcid, "LCIDM", "time", "mass_flow")
        return deck.table_file(stem, t, m, "time [s],mass flow [kg/s]")

    if lcidm0:
        injected = [g for g in gases if g["fmass"] > 0]
        if len({g["lcidt"] for g in injected}) != 1:
            raise kw.error("with LCIDM0 ventsim needs one temperature curve LCIDT shared by the injected gases")
        return [{"name": "inflator", "type": "mass_temperature", "mass_flow": mass_flow(lcidm0, f"{name}_mass_flow"),
                 "temperature": temperature(injected[0]["lcidt"], f"{name}_temperature"),
                 "gas": {n: g["fmass"] for n, g in zip(names, gases) if g["fmass"] > 0}}]
    injected = [(i, n, g) for i, (n, g) in enumerate(zip(names, gases)) if g["lcidm"]]
    return [{"name": f"inflator{i + 1}" if len(injected) > 1 else "inflator", "type": "mass_temperature",
             "mass_flow": mass_flow(g["lcidm"], f"{name}_gas{i + 1}_mass_flow"),
             "temperature": temperature(g["lcidt"], f"{name}_gas{i + 1}_temperature"), "gas": {n: 1.0}}
            for i, n, g in injected]


def hybrid_gas(deck, kw, cards, name):
    """([species], cavity state, vents, pop pressure) of an *AIRBAG_HYBRID."""
    atmost, atmosp, _, _, cc, hconv = fields(kw, cards[1], W10, "ffffff")
    refuse(kw, cards[1], ("HCONV",), (hconv,))
    if cc not in (None, 1.0):
        raise kw.error(f"CC = {cc}: ventsim reads consistent units (CC = 1) only", cards[1][1])
    c23, lcc23, a23, lca23, cp23, lcp23, ap23, lcap23 = fields(kw, cards[2], W10, "fififif" + "i")
    refuse(kw, cards[2], ("LCC23", "LCA23", "LCP23", "LCAP23"), (lcc23, lca23, lcp23, lcap23))
    opt, pvent, ngas, lcefr, lcidm0, vntopt = fields(kw, cards[3], W10, "ifiiii")
    refuse(kw, cards[3], ("OPT", "LCEFR", "VNTOPT"), (opt, lcefr, vntopt))
    if not (atmost and atmost > 0 and atmosp and atmosp > 0 and ngas and ngas > 0):
        raise kw.error("ATMOST, ATMOSP and NGAS must be > 0", cards[1][1])
    gases = _gases(deck, kw, cards, ngas)
    names = [f"{name}_gas{i + 1}" for i in range(ngas)]
    species = [{"name": n, "molar_mass": g["M"], "cp": g["cp"]} for n, g in zip(names, gases)]
    initial = {n: g["initm"] for n, g in zip(names, gases) if g["initm"] > 0}
    if not initial:
        raise kw.error("no gas has an initial mass fraction INITM > 0")
    state = {"pressure": deck.si(atmosp, "pressure"), "temperature": float(atmost), "gas": initial}
    inflators = _inflators(deck, kw, name, gases, names, lcidm0)
    if inflators:
        state["inflator"] = inflators
    return species, state, [("vent", c23, a23), ("porosity", cp23, ap23)], pvent
