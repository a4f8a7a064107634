#!/usr/bin/python3
# The seed paper's preprocessing, reproduced for the city benchmark (scripts/bench-city.sh): an OSM
# XML file read with Python's XML parser, the building ways made into polygons, projected with
# GeoPandas to (Web) Mercator and written as JSON. It is the baseline `quakeview-prep city` is
# measured against side by side; it is not part of the product.
#
#   /usr/bin/python3 scripts/paper-approach.py INPUT.osm OUTPUT.json
import sys
import xml.etree.ElementTree as ET

import geopandas as gpd
from shapely.geometry import Polygon


def main():
    if len(sys.argv) != 3:
        print("usage: paper-approach.py INPUT.osm OUTPUT.json", file=sys.stderr)
        return 2
    root = ET.parse(sys.argv[1]).getroot()
    nodes = {}
    for node in root.iter("node"):
        nodes[node.get("id")] = (float(node.get("lon")), float(node.get("lat")))
    rows = []
    for way in root.iter("way"):
        tags = {t.get("k"): t.get("v") for t in way.iter("tag")}
        if "building" not in tags:
            continue
        refs = [nd.get("ref") for nd in way.iter("nd")]
        if len(refs) < 4 or refs[0] != refs[-1] or any(r not in nodes for r in refs):
            continue
        rows.append({"id": way.get("id"), "height": tags.get("height"), "levels": tags.get("building:levels"),
                     "geometry": Polygon([nodes[r] for r in refs])})
    frame = gpd.GeoDataFrame(rows, geometry="geometry", crs="EPSG:4326").to_crs("EPSG:3857")
    with open(sys.argv[2], "w") as out:
        out.write(frame.to_json())
    print(f"{len(rows)} buildings")
    return 0


if __name__ == "__main__":
    sys.exit(main())
