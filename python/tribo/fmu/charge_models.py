"""The charge models an FMU includes and the enumerations it declares, read from its
modelDescription, so that a charge model added to the registry (src/chute/charge/charge_registry.def)
reaches the package without an edit here.

Each registered model <name> gives both FMUs its switch parameter charge_model_<name> (of
the enumeration tribo.Switch) and, in FMI 3.0, its per-segment array: segment_charge_<name>
in the dimensionless FMU, segment_sigma_<name> in the SI one (the names the tables,
src/chute/quantities.def and src/si/si_quantities.def, make of a registry row).
"""

SWITCH_PREFIX = "charge_model_"
SWITCH_TYPE = "tribo.Switch"
ARRAY_PREFIXES = ("segment_charge_", "segment_sigma_")


def charge_models(md) -> tuple[str, ...]:
    """The registered charge models, in the registry's order."""
    return tuple(v.name[len(SWITCH_PREFIX):] for v in md.modelVariables
                 if v.name.startswith(SWITCH_PREFIX) and v.declaredType is not None
                 and v.declaredType.name == SWITCH_TYPE)


def segment_arrays(md) -> dict[str, str]:
    """Charge model -> the name of its per-segment array, for each model whose array the
    FMU has (FMI 3.0 only: FMI 2.0 has no arrays)."""
    arrays = {v.name for v in md.modelVariables if v.dimensions}
    return {model: prefix + model for model in charge_models(md) for prefix in ARRAY_PREFIXES
            if prefix + model in arrays}


def enumeration(md, type_name: str) -> dict[str, int]:
    """Item name -> value of an enumeration the FMU declares (e.g. "tribo.MotionClass"), in
    the order of its items; KeyError naming the declared ones if there is none so named."""
    for t in md.typeDefinitions:
        if t.name == type_name and t.type == "Enumeration":
            return {item.name: int(item.value) for item in t.items}
    raise KeyError(f"{type_name}: the FMU declares the enumerations "
                   f"{', '.join(t.name for t in md.typeDefinitions if t.type == 'Enumeration')}")
