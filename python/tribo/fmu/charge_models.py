"""The charge models an FMU includes and the enumerations it declares, read from its
modelDescription, so that a charge model added to the registry (src/chute/charge/charge_registry.def)
reaches the package without an edit here.

Each registered model <name> gives both FMUs its switch parameter charge_model_<name> (of
the enumeration tribo.Switch) and, in FMI 3.0, its per-segment array: segment_charge_<name>
in the dimensionless FMU, segment_sigma_<name> in the SI one (the names the tables,
src/chute/quantities.def and src/si/si_quantities.def, make of a registry row).

The SI FMU's outputs of each model are named by the model too: charge_<name>,
charge_per_length_<name>, charge_to_mass_<name>, sigma_mean_<name>, capped_fraction_<name>,
charge_lost_<name>; the dimensionless FMU's mean charge of a model is Q_<name> where the
model has one (`mean_charges`). The package makes its column names from the model list
(`per_model`), so that a new model's columns appear in every table.

Models are selected by their switches only: the parameter `charge_model` (a bitmask of the
first two models) is refused in one line naming the switches (`REMOVED`, fmu/names.py).
"""

from .image import per_description

SWITCH_PREFIX = "charge_model_"
SWITCH_TYPE = "tribo.Switch"
ARRAY_PREFIXES = ("segment_charge_", "segment_sigma_")
MEAN_CHARGE_PREFIX = "Q_"
# parameter name -> why the package refuses it, told with the FMU's switches
REMOVED = {"charge_model": "charge_model was removed: each charge model has its own switch, "
                           "{switches} (1 on, 0 off)"}


@per_description
def charge_models(md) -> tuple[str, ...]:
    """The registered charge models, in the registry's order."""
    return tuple(v.name[len(SWITCH_PREFIX):] for v in md.modelVariables
                 if v.name.startswith(SWITCH_PREFIX) and v.declaredType is not None
                 and v.declaredType.name == SWITCH_TYPE)


def switches(models) -> list[str]:
    """The switch parameters of the models: charge_model_<name>."""
    return [SWITCH_PREFIX + m for m in models]


def per_model(prefixes, models) -> list[str]:
    """Column names, a prefix at a time, each for every model: per_model(("charge_",
    "charge_to_mass_"), ("static", "sliding")) -> charge_static, charge_sliding,
    charge_to_mass_static, charge_to_mass_sliding."""
    return [prefix + m for prefix in prefixes for m in models]


def mean_charges(md) -> tuple[str, ...]:
    """The models whose mean charge Q_<name> the FMU outputs (the dimensionless FMU's)."""
    outputs = {v.name for v in md.modelVariables if v.causality == "output"}
    return tuple(m for m in charge_models(md) if MEAN_CHARGE_PREFIX + m in outputs)


def removed_message(md, name: str) -> str | None:
    """The line that refuses a removed parameter, naming the FMU's switches (None for
    another name)."""
    if name not in REMOVED:
        return None
    return REMOVED[name].format(switches=", ".join(switches(charge_models(md))))


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
