"""The derivation document's expressions as SymPy objects."""

from __future__ import annotations

import json
import re
from typing import Any, Dict, List

_DOT = re.compile(r"dot\((\w+)\)")


def _names(document: Dict[str, Any]) -> List[str]:
    names = document["names"]
    parameters = [parameter["name"] for parameter in names["parameters"]]
    velocities = [f"dot_{q}" for q in names["coordinates"]]
    return names["coordinates"] + velocities + parameters + names["momenta"] + names["inputs"]


def derived_expressions(document_json: str) -> Dict[str, Any]:
    """``mass_matrix``, ``constraint_matrix``, ``kinetic_energy`` and
    ``potential_energy`` of a derivation document
    (``Model.document("json")``), read into SymPy, and the reduced form's
    ``structure_matrix`` and ``hamiltonian`` where it is derived exactly (a
    model whose exact reduced form is too large, such as the bicycle, has
    its reduced form structured in the generated code only)."""
    import sympy

    document = json.loads(document_json)
    symbols = {name: sympy.Symbol(name) for name in _names(document)}
    functions = {"sin": sympy.sin, "cos": sympy.cos, "tan": sympy.tan, "sqrt": sympy.sqrt,
                 "exp": sympy.exp, "ln": sympy.log, "asin": sympy.asin, "acos": sympy.acos,
                 "atan": sympy.atan, "atan2": sympy.atan2}

    def expression(text: str) -> Any:
        python = _DOT.sub(r"dot_\1", text).replace("^", "**")
        return sympy.parse_expr(python, local_dict={**symbols, **functions}, evaluate=True)

    def matrix(entry: Dict[str, Any]) -> Any:
        return sympy.Matrix([[expression(text) for text in row] for row in entry["text"]])

    lagrange = document["lagrange_dalembert"]
    reduced = document["port_hamiltonian"]
    mass_matrix = matrix(lagrange["mass_matrix"])
    qdot = sympy.Matrix([symbols[f"dot_{q}"] for q in document["names"]["coordinates"]])
    derived = {
        "mass_matrix": mass_matrix,
        "constraint_matrix": matrix(lagrange["constraint_matrix"]),
        "kinetic_energy": sympy.expand((qdot.T * mass_matrix * qdot)[0, 0] / 2),
        "potential_energy": expression(lagrange["potential"]["text"]),
    }
    if "structure_matrix" in reduced:
        derived["structure_matrix"] = matrix(reduced["structure_matrix"])
        derived["hamiltonian"] = expression(reduced["hamiltonian"]["text"])
    return derived
