"""Write cavity/data/coolprop_fits.json: the CoolProp cp0 fits of every built-in species, made afresh with the
installed CoolProp (run after a CoolProp upgrade: ``python cavity/data/make_coolprop_fits.py``)."""
from cavity.species import BUILTIN_COOLPROP_NAMES, coolprop_fit_key, fit_species_from_coolprop, species_record
from cavity.species_fits import SHIPPED, coolprop_version, write_json


def main():
    fits = {coolprop_fit_key(fluid, None, 100.0): species_record(fit_species_from_coolprop(fluid))
            for fluid in sorted(set(BUILTIN_COOLPROP_NAMES.values()))}
    write_json(SHIPPED, {"coolprop": coolprop_version(), "fits": fits})
    print(f"wrote {SHIPPED} ({len(fits)} fits, CoolProp {coolprop_version()})")


if __name__ == "__main__":
    main()
