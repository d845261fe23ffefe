"""MkDocs hook: the site carries bench/results/ too.

The benchmarks write their dated results into bench/results/, outside docs_dir, and
the pages link there with paths relative to the repository (`../bench/results/...`),
which also resolve when the Markdown is read in the repository itself. This hook adds
those files to the site at the same place, so that MkDocs can check the links and the
built site serves their targets.
"""

import os
import posixpath

from mkdocs.structure.files import File, InclusionLevel

RESULTS = "bench/results"


def on_files(files, config):
    root = os.path.dirname(os.path.abspath(config.config_file_path))
    folder = os.path.join(root, RESULTS)
    for name in sorted(os.listdir(folder)):
        if not os.path.isfile(os.path.join(folder, name)):
            continue
        site_uri = posixpath.join(RESULTS, name)
        # Where the file would go if it were inside docs_dir at that path.
        dest_uri = File(site_uri, None, config.site_dir, config.use_directory_urls).dest_uri
        files.append(File(posixpath.join("..", site_uri), config.docs_dir, config.site_dir,
                          config.use_directory_urls, dest_uri=dest_uri,
                          inclusion=InclusionLevel.NOT_IN_NAV))
    return files
