"""sphinx-gallery image scraper for tumble's figures, which never touch pyplot.

tumble.viz returns bare :class:`matplotlib.figure.Figure` objects (see tumble/viz/_backend.py:
pyplot's global list would keep them alive), so sphinx-gallery's matplotlib scraper, which asks
pyplot for its figures, does not see them. This one saves every Figure bound to a name in the
script's globals (``fig = figure_omega(traj)``) the first time a block leaves it there, in the
order they appear; pyplot's own figures are left to the matplotlib scraper.

It runs before the matplotlib scraper (docs/conf.py), while pyplot still holds its figures, and
tells them apart by asking pyplot which figures it holds, then remembers them: once the
matplotlib scraper has closed a pyplot figure nothing on the figure says where it came from
(matplotlib >= 3.11 gives a closed figure a fresh canvas without a manager), and saving it
again drew the figure twice on the page (issue 28).
"""

from __future__ import annotations

from matplotlib.figure import Figure


def tumble_figures(block, block_vars, gallery_conf):
    import matplotlib.pyplot as plt
    from sphinx_gallery.scrapers import figure_rst

    seen = block_vars.setdefault("tumble_figures_seen", set())
    seen.update(id(plt.figure(number)) for number in plt.get_fignums())  # pyplot's: its scraper saves them
    names = block_vars["image_path_iterator"]
    paths = []
    for value in list(block_vars["example_globals"].values()):
        if isinstance(value, Figure) and id(value) not in seen:
            seen.add(id(value))
            path = next(names)
            value.savefig(path, dpi=100)
            paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])


def _get_sg_image_scraper():
    return tumble_figures
