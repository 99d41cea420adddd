"""The kinds of warning `canspec import` gives, for the README's corpus table: a short name per
kind, recognised by the words of its message (importer/dbctext.py, tospec.py, clashes.py)."""

from __future__ import annotations

KINDS = (  # (kind, words its message holds), first match wins
    ("29-bit ID without the extended flag", "no extended flag: taken as 29-bit"),
    ("ID wider than 29 bits: message left out", "does not fit 29 bits"),
    ("frame ID used twice (two buses): message left out", "another bus of the file"),
    ("number written `.25`", "without a leading 0"),
    ("name starting with a digit", "starts with a digit"),
    ("name not a DBC identifier: `_` for each other sign", "is not a DBC identifier"),
    ("statement without `;`", "without its closing ';'"),
    ("`CM_` without object type", "CM_ without an object type"),
    ("`CM_ SG_` without signal name: dropped", "CM_ SG_ without a signal name"),
    ("`VAL_` for a missing signal: dropped", "which has no such signal"),
    ("multiplexing canspec cannot say: message left out", "top-level multiplexers"),
    ("scaled or signed multiplexer: message left out", "is not an unsigned integer with factor 1"),
    ("multiplexed counter or checksum: role dropped", "is multiplexed or a multiplexer: role dropped"),
    ("multiplexer range leaving out a page: dropped", "leaves out values that select a page"),
    ("multiplexer value beyond its bits: dropped", "multiplexer values above"),
    ("page no multiplexer value selects: left out", "no multiplexer value that selects it fits"),
    ("page of a left-out multiplexer: left out", "its multiplexer"),
    ("multiplexer (M) selecting no page: a plain field", "selects no page: taken as a plain field"),
    ("page selector not marked M: taken as multiplexer", "taken as their multiplexer"),
    ("overlapping signal: left out", "overlaps"),
    ("signal leaving its frame: left out", "leaves its"),
    ("value label outside the field: dropped", "does not fit its"),
    ("node not declared in `BU_`: added", "not declared in BU_"),
    ("more than 8 bytes without FD format: taken as FD", "no CAN FD frame format"),
    ("no bit rate: 500 kbit/s assumed", "no bit rate given"),
    ("no FD data bit rate: assumed", "no data bit rate"),
    ("BusType the frames contradict: written from the frames", "BusType is"),
    ("range holding no value: dropped", "holds no value of the field"),
    ("C/Rust name clash: spec name renamed", "name clashes"),
    ("attribute value its definition refuses: left out", "is refused by its definition"),
    ("ENUM attribute value not an index of its values: dropped", "is not an index of its ENUM"),
    ("attribute of other objects: left out", "objects: left out"),
    ("scaled float: scaling dropped", "scaling dropped"),
    ("not a frame length: message left out", "not a CAN frame length"),
    ("signal over 64 bits: left out", "bits long: left out"),
    ("value labels of a float signal: dropped", "has value labels: dropped"),
    ("not UTF-8: encoding guessed", "not UTF-8"),
    ("message name twice: later one renamed", "is given to two messages"),
    ("SG_MUL_VAL_ naming a signal its own multiplexer: message left out", "as its own multiplexer"),
    ("multiplexed signal without multiplexer: message left out", "has no multiplexer of the message"),
    ("cantools log line", "cantools: "),
)


def kind_of(text: str) -> str:
    return next((kind for kind, words in KINDS if words in text), "other")
