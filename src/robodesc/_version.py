"""robodesc's version, in a leaf module so that the emitters can name it without importing the API."""

__version__ = "0.1.0"
