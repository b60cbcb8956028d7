"""Particle populations: a feed drawn with a seed, each particle run down the chute through
the SI FMU (`tribo.population`, tribo population).

    distributions   a feed variable's distribution, as text, drawn with a seed
    feed_variables  what a feed draws, the units, the reference feed and chute (constants)
    feed            a feed, its seeded draw, the columns of a particle's row
    particle        one particle's run and its row (numpy and fmpy only: what a Dask
                    worker process imports)
    runner          a population into a folder, resumable
    summary         q/m statistics overall and by shape and size class
    plot            a population's figure
"""
