"""The separation line (docs/line.md): grains down the SI chute and through the free-fall
separator, one grain or a population (grain), a binary mixture of two particle materials
and its voltage sweep with grade and recovery (mixture), the figure (plot); the defaults the
command shows (defaults)."""
