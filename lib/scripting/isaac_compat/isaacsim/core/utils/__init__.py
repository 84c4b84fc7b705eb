"""isaacsim.core.utils"""
