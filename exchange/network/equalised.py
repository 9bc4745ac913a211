"""Thresholds of the equalised mode of a two-way pneumatic exchange (held closed while its two sides agree)."""

#: Relative pressure difference |Δp|/max(p_a, p_b) [-] below which a two-way pneumatic exchange is held closed
#: ("equalised"): at Δp = 0 its law is a sliding mode (it pushes back from both sides, with a slope that makes the
#: equalised state stiff for explicit steps), so once the two sides agree to this level the exchange carries no
#: flow until the rest of the network drives them apart again.
EQUALISED_BELOW = 1e-10
#: |Δp|/max(p_a, p_b) [-] above which an equalised exchange opens again (100× the entry level: no chattering).
RELEASED_ABOVE = 1e-8
