"""Linear modal analysis of the rotating blisk + ring (paper §2.3): the methods (:mod:`.analysis`) and
the modal stage of the campaign (:mod:`.stage`)."""
