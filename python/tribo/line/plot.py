"""The figure of a mixture's voltage sweep: grade and recovery of both products against the
electrode voltage (left), and where each material's mass went (right: the share of its fed
mass in each product, on the plates, not collected). Legends sit beside the panels, clear
of the data. Where grains stayed on the chute (at rest, or still on it at the horizon: they
never enter the separator), the title's second line says how many and their share of each
material's mass; the right panel draws that share too."""

from ..fmu.names import format_number
from ..materials import material
from ..plotting import distinct_colours, legend, plt, save


def write_line_figure(table, line, n: int, seed: int, path: str, stayed: str = "") -> str:
    """stayed: what the title says of the grains that stayed on the chute (mixture.py's
    stayed_text, a line per material), "" where none did."""
    materials = [material(p, "particle").key for p in line.particles]
    colours = distinct_colours(len(materials))
    kv = table["voltage"] / 1e3
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 4.8), constrained_layout=True)
    for m, c in zip(materials, colours):
        ax.plot(kv, table[f"grade_{m}"], "-o", color=c, label=f"grade of the {m} product")
        ax.plot(kv, table[f"recovery_{m}"], "--s", color=c, mfc="none",
                label=f"recovery of {m}")
    ax.set_xlabel("electrode voltage U (kV)")
    ax.set_ylabel("grade, recovery (mass fraction, 1)")
    ax.set_ylim(-0.02, 1.02)
    ax.grid(alpha=0.3)
    ax.set_title("grade and recovery of each product")
    legend(ax, outside=True)
    styles = [("neg_side", "-", "in the -x product"), ("pos_side", "--", "in the +x product"),
              ("plates", ":", "caught on a plate")]
    if stayed:
        styles.append(("not_exited", "-.", "stayed on the chute"))
    for m, c in zip(materials, colours):
        fed = table[f"fed_{m}"]
        plates = table[f"plate_neg_{m}"] + table[f"plate_pos_{m}"]
        for key, ls, what in styles:
            values = plates if key == "plates" else table[f"{key}_{m}"]
            ax2.plot(kv, values / fed, linestyle=ls, color=c, marker=".", label=f"{m} {what}")
    ax2.set_xlabel("electrode voltage U (kV)")
    ax2.set_ylabel("share of the material's fed mass (1)")
    ax2.set_ylim(-0.02, 1.02)
    ax2.grid(alpha=0.3)
    ax2.set_title("where each material goes (plates: scraped into their side's product)")
    legend(ax2, outside=True)
    chute = dict(line.chute)
    title = (f"{n} grains, {' + '.join(materials)} ({format_number(line.fraction)} : "
             f"{format_number(1 - line.fraction)} by mass) on "
             f"{format_number(chute.get('chute_length', 0.3))} m of {line.wall}, "
             f"{line.charge_model} charge model, splitter at x = "
             f"{format_number(line.splitter * 1e3)} mm, seed {seed}")
    if stayed:
        title += f"\ngrains that stayed on the chute (never in the separator):\n{stayed}"
    fig.suptitle(title, fontsize=10)
    return save(fig, path)
