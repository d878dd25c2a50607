"""Placeholder: exercises of this stage are being written."""
