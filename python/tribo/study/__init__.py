"""The paper's study (docs/model.md section 7) through the FMU.

    paper       its runs: the friction cases, the dashpots, a run at a roundness
    runner      the study: the grid's runs, eps_t, figures and tables into a folder
    transition  the transition roundness eps_t: coarse grid, then multi-section
    figures     the study's figures
    tables      the study's tables (CSV and markdown) and study.md
"""
