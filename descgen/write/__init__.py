"""What is written to disk besides rendered text: the generated packages switched in atomically
(package.py), the pose pictures and the frames drawing of the evidence."""
