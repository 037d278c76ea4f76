"""USD layers without usd-core: an in-memory layer model and its ``.usda`` / ``.usdc`` writers."""
