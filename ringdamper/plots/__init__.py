"""Figures of the campaign and of its studies (matplotlib, Agg backend), drawn from the data the
stages and studies return; they import the layers below them, never the studies."""
import matplotlib

matplotlib.use("Agg")


def save_figure(fig, path, dpi: int = 110) -> None:
    """Lay ``fig`` out, write it to ``path`` and close it."""
    import matplotlib.pyplot as plt

    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
