"""isaacsim.storage"""
