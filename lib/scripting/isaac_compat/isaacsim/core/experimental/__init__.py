"""isaacsim.core.experimental"""
