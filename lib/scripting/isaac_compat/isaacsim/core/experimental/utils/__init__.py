"""isaacsim.core.experimental.utils"""
