"""isaacsim: the Isaac Sim modules the layer provides; an Isaac extension tree beside a script joins this package."""
