"""Charge-per-impact maps: the charge one wall impact transfers, over impact speed, angle,
orientation and roundness, through the SI FMU (`tribo.impact_map`, `tribo.ImpactMap`,
tribo impact-map).

    defaults the defaults the command shows (constants)
    episode  one impact episode (run_end = first_liftoff) and a map's grid
    map      a map's runs, table and metadata, and the lookup ImpactMap
    plot     a map's figure
"""
