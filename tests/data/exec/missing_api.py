import omni.replicator.core as rep

rep.create.cube()
