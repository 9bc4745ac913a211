"""An Abaqus/Explicit fluid-cavity deck -> the scene dict a TOML file gives (``cases.scene.files.scene_from_dict``).

Keywords that matter to the gas are mapped (docs/decks.md lists each one and what it becomes); keywords of the
structure (materials, sections, output, general contact) are listed once as ``ignored: *KEYWORD (line N)``; a
keyword that would change the answer if it were left out, or data ventsim cannot express, is an error naming
the file and line.
"""
from __future__ import annotations

from pathlib import Path

from cases.scene.errors import SceneError
from cases.scene.schema import suggest
from cases.decks import abaqus_bodies, abaqus_exchange, abaqus_fluid, abaqus_inflator
from cases.decks.abaqus_lexer import read_keywords
from cases.decks.abaqus_mesh import face_nodes, read_mesh
from cases.decks.abaqus_parts import flatten_parts
from cases.decks.deck_io import deck_error, faces_area, ignored_line
from cases.decks.imported import Imported
from cases.decks.units import unit_system
from cases.decks.write_scene import csv_text, obj_text

__all__ = ["read_abaqus"]

MESH = {"NODE", "ELEMENT", "NSET", "ELSET", "SURFACE", "PARAMETER", "END STEP"}
FLUID = {"FLUID BEHAVIOR", "MOLECULAR WEIGHT", "CAPACITY", "FLUID DENSITY", "FLUID BULK MODULUS", "FLUID EXPANSION"}
INFLATOR = {"FLUID INFLATOR", "FLUID INFLATOR PROPERTY", "FLUID INFLATOR MIXTURE", "FLUID INFLATOR ACTIVATION"}
EXCHANGE = {"FLUID EXCHANGE", "FLUID EXCHANGE PROPERTY", "FLUID EXCHANGE ACTIVATION"}
CONTACT = {"SURFACE INTERACTION", "BLOCKAGE", "SURFACE BEHAVIOR", "CONTACT PROPERTY ASSIGNMENT", "RIGID BODY",
           "BOUNDARY"}
#: keywords whose omission would change the model: an error, not an "ignored" line
REFUSED = {"NGEN": "generated nodes", "NFILL": "generated nodes", "NCOPY": "copied nodes",
           "ELGEN": "generated elements", "FLUID LINK": "fluid links", "STATIC": "Abaqus/Standard steps",
           "FLUID FLUX": "fluid fluxes"}


class Deck:
    """What has been read of one deck, and the helpers that turn its values into scene values."""

    def __init__(self, path: Path, units: str):
        self.path, self.units, self.stem = path, unit_system(units), path.stem
        self.files, self.notes, self.ignored = {}, [], {}
        self.abs_zero, self.gas_constant = 0.0, None
        self.behaviors, self.used_species = {}, set()
        self.initial_pressure, self.initial_temperature = {}, {}
        self.inflator_props, self.inflators, self.inflator_activation = {}, [], {}
        self.exchange_props, self.exchanges, self.exchange_activation = {}, [], {}
        self.interactions, self.assignments, self.rigid_bodies, self.boundaries, self.bodies = {}, [], [], {}, {}
        self.amplitudes, self.cavity_kws, self.time_end, self.output_interval, self.title = {}, [], None, None, ""
        self.step_kw, self.transforms, self.edge_contact = None, [], False
        self.mesh = None

    suggest = staticmethod(suggest)

    def si(self, value, quantity):
        return self.units.si(value, quantity)

    def kelvin(self, theta, kw):
        t = float(theta) - self.abs_zero
        if not t > 0.0:
            raise kw.error(f"absolute temperature {t!r} K <= 0: give *PHYSICAL CONSTANTS, ABSOLUTE ZERO= or an "
                           "initial TEMPERATURE on the reference node")
        return t

    def behavior_kind(self, name, kw):
        b = self.behaviors[name]
        if "M" in b:
            if "cp" not in b:
                raise b["kw"].error(f"{name}: an ideal gas needs *CAPACITY, TYPE=POLYNOMIAL")
            return "gas"
        if "density" in b and "K" in b:
            return "hydraulic"
        raise b["kw"].error(f"{name}: needs *MOLECULAR WEIGHT and *CAPACITY (ideal gas) or *FLUID DENSITY and "
                            "*FLUID BULK MODULUS (hydraulic)")

    def gas_constant_scale(self, kw):
        if self.gas_constant is None:
            self.notes.append("no *PHYSICAL CONSTANTS, UNIVERSAL GAS CONSTANT: ventsim's 8.314462618 J/(mol K)")
            self.gas_constant = abaqus_fluid.R_U / self.units.factor("molar_heat")
        r_si = self.si(self.gas_constant, "molar_heat")
        return 1.0 if r_si == abaqus_fluid.R_U else abaqus_fluid.R_U / r_si

    def amplitude(self, name, kw, smooth_step=False):
        """(times, values) of amplitude ``name``; a SMOOTH STEP only where ``smooth_step`` (its integral)."""
        if name not in self.amplitudes:
            raise kw.error(f"AMPLITUDE={name}: no *AMPLITUDE of that name{suggest(name, self.amplitudes)}")
        akw, t, a = self.amplitudes[name]
        if not smooth_step and akw.label("DEFINITION") == "SMOOTH STEP":
            raise kw.error(f"AMPLITUDE={name} is a SMOOTH STEP: ventsim's tables are piecewise linear (here only an "
                           "INFLATION TIME AMPLITUDE may be a smooth step)")
        return t, a

    def step_end(self, kw):
        if self.time_end is None:
            raise kw.error("no *STEP with *DYNAMIC, EXPLICIT and a time period")
        return self.time_end

    def table_file(self, stem, x, y, header):
        name = f"{self.stem}/{stem}.csv"
        self.files[name] = csv_text(x, y, header)
        return name

    def mesh_file(self, stem, faces):
        name = f"{self.stem}/{stem}.obj"
        xyz = {n: tuple(self.si(c, "length") for c in self.mesh.nodes[n]) for f in faces for n in f}
        self.files[name] = obj_text(faces, xyz, f"{stem}: from {self.path.name}")
        return name

    def mesh_error(self, surface, line, message):
        return deck_error(self.mesh.surfaces[surface].file, line, "SURFACE", message)

    def faces(self, surface, kw, outward):
        return face_nodes(self.mesh, self.mesh.surfaces[surface], outward=outward, file=kw.file, line=kw.line)

    def surface_area(self, faces):
        return faces_area(faces, {n: [self.si(c, "length") for c in self.mesh.nodes[n]] for f in faces for n in f})

    def blockers(self, leak, cavity_surface, act):
        return abaqus_bodies.blockers(self, leak, cavity_surface, act)

    def ignore(self, kw, why=""):
        if kw.name not in self.ignored:
            self.ignored[kw.name] = ignored_line(kw.name, kw.file, kw.line, self.path, why)


def _step(deck, kw):
    if kw.name == "STEP":
        if deck.step_kw is not None:
            raise kw.error(f"a second step (the first is at line {deck.step_kw.line}): ventsim reads one step")
        deck.step_kw = kw
    elif kw.name == "DYNAMIC":
        if not kw.param("EXPLICIT"):
            raise kw.error("ventsim reads *DYNAMIC, EXPLICIT steps")
        if not kw.data or len(kw.data[0].fields) < 2:
            raise kw.error("missing data line ', time period'")
        deck.time_end = abaqus_fluid.floats(kw, kw.data[0], 1, "time period")[1]
    elif kw.name == "OUTPUT":
        if not kw.param("HISTORY"):
            return False
        if kw.number("TIME INTERVAL"):
            deck.output_interval = kw.number("TIME INTERVAL")
        elif kw.number("NUMBER INTERVAL"):
            deck.output_interval = ("n", kw.number("NUMBER INTERVAL"))
    return True


def _amplitude(kw):
    """(keyword, times, values) of an *AMPLITUDE: TABULAR pairs (any number per line), EQUALLY SPACED values
    (FIXED INTERVAL=, BEGIN=), or SMOOTH STEP pairs (kept for the inflation-time delay only)."""
    definition = kw.label("DEFINITION") or "TABULAR"
    if definition not in ("TABULAR", "EQUALLY SPACED", "SMOOTH STEP"):
        raise kw.error(f"DEFINITION={definition}: ventsim reads TABULAR, EQUALLY SPACED and SMOOTH STEP amplitudes")
    values = [v for d in kw.data for v, f in zip(abaqus_fluid.floats(kw, d, 1, "amplitude data"), d.fields) if f]
    if definition == "EQUALLY SPACED":
        dt, begin = kw.number("FIXED INTERVAL"), kw.number("BEGIN", 0.0)
        if not dt or dt <= 0:
            raise kw.error("EQUALLY SPACED needs FIXED INTERVAL= > 0")
        return kw, [begin + i * dt for i in range(len(values))], values
    if len(values) % 2 or not values:
        raise kw.error("expected time, amplitude pairs", kw.data[-1].line if kw.data else None)
    times = values[0::2]
    if any(b < a for a, b in zip(times, times[1:])):
        raise kw.error("the times must not decrease")
    return kw, times, values[1::2]


def _general(deck, kw):
    """*HEADING, *PHYSICAL CONSTANTS, *AMPLITUDE, *INITIAL CONDITIONS, steps: True when handled."""
    if kw.name == "HEADING":
        deck.title = kw.data[0].fields[0] if kw.data else ""
    elif kw.name == "PHYSICAL CONSTANTS":
        deck.abs_zero = kw.number("ABSOLUTE ZERO", 0.0)
        deck.gas_constant = kw.number("UNIVERSAL GAS CONSTANT")
    elif kw.name == "AMPLITUDE":
        deck.amplitudes[kw.label("NAME", required=True)] = _amplitude(kw)
    elif kw.name == "INITIAL CONDITIONS":
        return abaqus_fluid.read_initial(deck, kw)
    elif kw.name in ("STEP", "DYNAMIC", "OUTPUT"):
        return _step(deck, kw)
    else:
        return False
    return True


def _family(name):
    for fam, names in (("fluid", FLUID), ("inflator", INFLATOR), ("contact", CONTACT)):
        if name in names:
            return fam
    return "contact" if name in ("CONTACT DAMPING", "FRICTION") else None


def _read(deck, blocks):
    parent = (None, None)  # (family, name) of the keyword that sub-options follow
    for kw in blocks:
        if kw.name in REFUSED:
            raise kw.error(f"{REFUSED[kw.name]} are not supported")
        if kw.name == "SYSTEM" and any(f not in ("", "0", "0.", "0.0") for d in kw.data for f in d.fields):
            raise kw.error("a shifted or rotated *SYSTEM is not supported")
        fam = _family(kw.name)
        above = parent[1] if parent[0] == fam else None
        if fam == "fluid":
            parent = (fam, abaqus_fluid.read_behaviors(deck, kw, None if kw.name == "FLUID BEHAVIOR" else above))
        elif fam == "inflator":
            parent = (fam, abaqus_inflator.read_inflator(deck, kw, above))
        elif kw.name in CONTACT:
            parent = (fam, abaqus_bodies.read_contact(deck, kw, above))
        elif kw.name == "CONTACT DAMPING":
            deck.ignore(kw, "damping acts on a dynamic body's contact force; deck bodies move as prescribed")
        elif kw.name == "FRICTION":
            deck.ignore(kw)
        elif kw.name == "CONTACT FORMULATION":
            deck.edge_contact |= "EDGE" in (kw.label("TYPE") or "")
            if "EDGE" not in (kw.label("TYPE") or ""):
                deck.ignore(kw)
        elif kw.name == "TRANSFORM":
            deck.transforms.append(kw)
            deck.ignore(kw, "local directions of nodal boundary conditions (refused on a moving rigid body)")
        else:
            parent = (None, None)
            if kw.name in EXCHANGE:
                abaqus_exchange.read_exchange(deck, kw)
            elif kw.name == "FLUID CAVITY":
                deck.cavity_kws.append(kw)
            elif kw.name not in MESH and not _general(deck, kw):
                deck.ignore(kw)


def _volume_keys(deck):
    import trimesh

    from cavity.volume import MeshError, closed_mesh_volume

    def keys(kw):
        surface, added = kw.label("SURFACE"), kw.number("ADDED VOLUME", 0.0)
        if surface is None:
            if not added:
                raise kw.error("needs SURFACE= or ADDED VOLUME=")
            return {"volume": deck.si(added, "volume")}
        if surface not in deck.mesh.surfaces:
            raise kw.error(f"SURFACE={surface}: no *SURFACE of that name{suggest(surface, deck.mesh.surfaces)}")
        faces = deck.faces(surface, kw, outward=True)
        name = deck.mesh_file(f"cavity_{kw.label('NAME').lower()}", faces)
        mesh = trimesh.load(trimesh.util.wrap_as_stream(deck.files[name]), file_type="obj", force="mesh")
        try:
            closed_mesh_volume(mesh, name=f"surface {surface}")
        except MeshError as exc:
            raise kw.error(str(exc)) from None
        return {"mesh": name, **({"added_volume": deck.si(added, "volume")} if added else {})}
    return keys


def _ambient(deck, ambients, cavities):
    p = {a[0] for a in ambients}
    if len(p) > 1:
        raise deck.cavity_kws[-1].error(f"cavities with different AMBIENT PRESSURE {sorted(p)}: the scene has one "
                                        "ambient")
    p_amb, t_amb = ambients[0] if ambients else (0.0, None)
    amb = {}
    if p_amb:
        amb["pressure"] = deck.si(p_amb, "pressure")
    if t_amb is not None:
        amb["temperature"] = deck.kelvin(t_amb, deck.cavity_kws[0])
    gas = next((c for c in cavities if "gas" in c), None)
    if gas is not None:
        amb.update(gas=dict(gas["gas"]), gas_by_mole=gas["gas_by_mole"])
    return amb


def _time(deck):
    end = deck.step_end(deck.step_kw or (deck.cavity_kws[0]))
    out = {"end": deck.si(end, "time")}
    if isinstance(deck.output_interval, tuple):
        out["output_interval"] = deck.si(end / deck.output_interval[1], "time")
    elif deck.output_interval:
        out["output_interval"] = deck.si(deck.output_interval, "time")
    return out


def read_abaqus(path, units: str = "SI") -> Imported:
    """Read the Abaqus deck at ``path`` (values in ``units``) into an :class:`Imported` scene."""
    path = Path(path)
    deck = Deck(path, units)
    blocks = flatten_parts(read_keywords(path))
    deck.mesh = read_mesh(blocks)
    for etype, (file, line) in deck.mesh.other_types.items():
        deck.ignored[f"ELEMENT {etype}"] = ignored_line(f"ELEMENT, TYPE={etype}", file, line, path,
                                                        "not a surface element (no cavity, vent or blocker)")
    _read(deck, blocks)
    if not deck.cavity_kws:
        raise SceneError(path, "", "no *FLUID CAVITY: nothing for ventsim to simulate")
    cavities, surfaces, ambients = {}, {}, []
    keys = _volume_keys(deck)
    for kw in deck.cavity_kws:
        node, entry, amb = abaqus_fluid.cavity_entry(deck, kw, keys)
        if node in cavities:
            raise kw.error(f"reference node {node} already belongs to cavity {cavities[node]['name']}")
        cavities[node], surfaces[node] = entry, kw.label("SURFACE")
        ambients.append(amb)
    abaqus_inflator.inflator_entries(deck, cavities)
    exchanges = abaqus_exchange.exchange_entries(deck, cavities, surfaces)
    amb = _ambient(deck, ambients, list(cavities.values()))
    if "pressure" not in amb and any(e["to"] == "ambient" for e in exchanges):
        raise deck.cavity_kws[0].error("an exchange with the environment needs AMBIENT PRESSURE= on the cavity")
    data = {"title": deck.title or f"imported from {path.name}", "time": _time(deck)}
    if amb:
        data["ambient"] = amb
    species = abaqus_fluid.species_entries(deck)
    for name, part in (("species", species), ("cavity", list(cavities.values())), ("exchange", exchanges),
                       ("body", list(deck.bodies.values()))):
        if part:
            data[name] = part
    return Imported(path.name, data, deck.files, list(deck.ignored.values()), deck.notes)
